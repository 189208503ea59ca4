// The interlace runner (docs/quilts.md): N ordinary camera views, or one quilt of them, mapped
// onto a display as the usual practice does: a barrier's image layer (the paper's Fig. 2 direct
// mapping) with its mask, or a lenticular panel's picture (Looking Glass's interlacing shader).
// And what an eye sees on a lenticular panel through its lenses (`lenticular simulate`).
// `parallax interlace`, `parallax lenticular simulate` and Python's interlace functions are
// spellings of these requests.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "parallax/core/math.h"
#include "parallax/image/image.h"
#include "parallax/jobs/display_request.h"
#include "parallax/jobs/interlace_request.h"
#include "parallax/jobs/reporter.h"

namespace parallax::jobs {

// One interlaced picture set in memory: a barrier's image and mask layers, or a lenticular
// panel's picture (mask empty), and render.json's record (without /outputs).
struct InterlaceResult {
  Image image, mask;
  std::string record;
};

// Reads the views (or the quilt) and writes request.output as `render` writes its layers: the
// layers (or the panel picture), the display's file and render.json. Everything is checked
// before anything is written.
void runInterlace(const InterlaceRequest& request, Reporter& reporter);

// The same in memory: `views` (leftmost camera first), or `quilt` cut into its tiles by
// request.quiltLayout (which it then needs); request.views and request.quilt only name them in
// messages and the record.
InterlaceResult interlaceInMemory(const InterlaceRequest& request, const std::vector<Image>& views,
                                  const Image& quilt, Reporter& reporter);

// ---- lenticular simulate --------------------------------------------------------------------

struct LenticularSimulateRequest {
  std::string image;  // the panel picture file
  // Its calibration (visual.json, lkg:NAME), distance (the design viewer in mm; 0: the cone
  // spans 1 m) and the lens reading to read the panel under (SimulatorRequest's lens).
  DisplayRequest display;
  // eye: display mm (origin the panel centre, z toward the viewer); default the centre of the
  // view cone at the design distance.
  std::optional<Vec3d> eye;
  std::string output = "out/lenticular-view.png";
};

// Writes request.output: the panel seen from the eye through the lenses.
void runLenticularSimulate(const LenticularSimulateRequest& request, Reporter& reporter);

// The same for a panel picture in memory (the calibration request.display describes).
Image lenticularViewInMemory(const LenticularSimulateRequest& request, const Image& panel,
                             Reporter& reporter);

}  // namespace parallax::jobs
