// The outputs shared by `render`, `render --quilt`, `interlace` and `lenticular render`: the
// display's two layer images with display.json and a render.json record of how they were made,
// written as one set.
#pragma once

#include <string>
#include <vector>

#include "parallax/display/display.h"
#include "parallax/image/image.h"
#include "parallax/importer/mesh_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/output_set.h"
#include "parallax/layers/layer_problem.h"
#include "parallax/scene/scene.h"

namespace parallax::jobs {

// The names a picture set of writePictureSet() writes: image.png, mask.png (with `mask`),
// image.pfm (`linear`), image-K.png and mask-K.png for `frames` > 1, the display's file and
// render.json; for OutputSet::check before the work.
std::vector<std::string> pictureSetNames(size_t frames, bool mask, bool linear,
                                         const std::string& displayFileName);

// Program, version, time, method and display file at the top of a render.json record, and
// /import: what loading the command's scenes did with each mesh file (importRecords()).
void startRenderRecord(JsonWriter& record, const std::string& method,
                       const std::string& displayFile, const ImportOptions& options,
                       const std::vector<Scene::ImportRecord>& imports);

// Refuses (naming `subject`) layers that would not fit in memory: the image layer's film
// (`filmColumns` wide: three per pixel with subpixel rays, times `views` for N ordinary views),
// the two layers and their 8-bit copies for the PNG writer.
void checkLayerMemory(const DisplayDesign& design, double filmColumns, double views,
                      const std::string& subject);

// Both estimates of `render` before it allocates: the layers (checkLayerMemory; with
// `directMapping` one ordinary view per interleaved view) and the time of `spp` samples per
// film pixel. `displayPath` names the display ("" = built-in) in the refusal.
void checkLayerWork(const DisplayDesign& design, bool directMapping, int spp, int threads,
                    const std::string& displayPath);

// The quilt of `render --quilt`: its 8-bit codes and PNG, the float quilt with `linear`, one
// view at a time, and the time; refusals name the quilt field ("{quilt} CxR") and the size.
void checkQuiltWork(int columns, int rows, int width, int height, int spp, int threads,
                    const std::string& sizeText, bool linear);

// Writes DIR/image.png, mask.png (image.pfm with `linear`), display.json and render.json (the
// record, with /outputs and /design added) as one set, and says where on stdout.
// Returns the line that says what was written.
std::string writeDisplayLayers(const std::string& output, const Image& image, const Image& mask,
                               const DisplayDesign& design, bool linear, JsonWriter& record);

// The display's own file written beside its pictures: display.json (a barrier) or visual.json
// (a lenticular calibration), and its key under /outputs ("display", "calibration").
struct DisplayFile {
  std::string name, text, recordKey;
  // A display made in code has no file: its sets hold the pictures and render.json alone.
  bool written() const { return !name.empty(); }
};

// A display's pictures as one set in `output`, with its file and render.json (the record, with
// /outputs added; /design is the caller's): one frame with a mask (writeDisplayLayers' files),
// several (writeLayerFrames'), or a panel picture without a mask (image.png). Returns the line
// that says what was written.
std::string writePictureSet(const std::string& output, const std::vector<LayerFrame>& frames,
                            bool linear, const DisplayFile& file, JsonWriter& record);

// Time-multiplexed layers (render --layers nmf --rank T): DIR/image-K.png and mask-K.png for
// K = 1..T, shown in turn, with display.json and render.json (/frames lists the pairs), as one
// set.
std::string writeLayerFrames(const std::string& output, const std::vector<LayerFrame>& frames,
                             const DisplayDesign& design, JsonWriter& record);

}  // namespace parallax::jobs
