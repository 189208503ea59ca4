// The one display factory (docs/architecture.md, "One display, every kind"): a display's
// description (io/display_file.h) and the camera's choices for it become a DisplayModel. Outside
// display/, io's reader and the two-layer simulator, this is the only code that asks which kind
// a display is; every runner works on the model it returns.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "parallax/camera/framing.h"
#include "parallax/display/display_model.h"
#include "parallax/display/view_filter.h"
#include "parallax/io/display_file.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/requests.h"
#include "parallax/scene/scene.h"

namespace parallax::jobs {

// The camera's choices for a display: render settings, not part of its physical description.
struct DisplayCameraRequest {
  bool subpixels = false;     // subpixels: one ray per R, G, B subpixel (barriers)
  ViewFilter filter;          // how a film sample's rays spread in angle
  double viewDistanceMm = 0;  // distance: a lenticular panel's design viewer (0: its default)
  // A lenticular panel's optics to render for (docs/lenticular.md, "The optics"), each unset:
  // the display's own. lens_spot: the focal spot in subpixels; bundles: parallel or converging.
  std::optional<double> lensSpot;
  std::string bundles;
};

// The lenticular optics that lens_spot and bundles ask for, over the design's own; unset when
// neither is given. Throws RequestError naming lens_spot (outside 0 to 12 subpixels) or bundles
// (neither parallel nor converging).
std::optional<LensOptics> lensReading(const LenticularDesign& design,
                                      const std::optional<double>& lensSpot,
                                      const std::string& bundles);
// A barrier has no lenses: throws RequestError naming lens_spot or bundles when either is given.
void refuseLensReading(const std::optional<double>& lensSpot, const std::string& bundles);

// A display built for a camera, and what a render writes beside its pictures.
struct BuiltDisplay {
  std::unique_ptr<DisplayModel> model;
  // The display as its file (display.json, or a calibration's visual.json), for output sets.
  DisplayFile file;
  std::optional<Framing> framing;  // how the scene was framed for it (makeFramedDisplay)
  // Every given and derived figure of its design under the JSON pointer `at`.
  void recordDesign(JsonWriter& record, const std::string& at) const;

  const DisplayModel& operator*() const { return *model; }
  const DisplayModel* operator->() const { return model.get(); }
};

// A barrier's design (with the file's camera settings); a lenticular calibration is refused,
// naming the file, for the commands that take barriers only.
DisplayDesign barrierDesignOf(const DisplayDescription& description);

// Builds the display. Throws RequestError for a choice its kind does not have (subpixels on a
// lenticular panel, a viewer distance on a barrier, whose distance is its design's).
BuiltDisplay makeDisplay(const DisplayDescription& description,
                         const DisplayCameraRequest& camera = {});

// The same for a render of `scene`: the display frames the scene for itself first (camera/
// framing.h: the placement's width, the zero-parallax plane, and for the depth budget a
// barrier's virtual gap or a lenticular panel's depth scale, display/depth_scaled_display.h)
// and `scene`'s placement becomes the framing's.
BuiltDisplay makeFramedDisplay(const DisplayDescription& description,
                               const DisplayCameraRequest& camera, const FramingRequest& framing,
                               Scene& scene);

// The checks of a framing request before any work (every kind of display takes one).
void checkFramingApplies(const DisplayDescription& description, const FramingRequest& framing);

// A display of any kind (io/display_file.h: "" the built-in barrier, a file of either kind, or
// lkg:NAME), the reader's warnings (defaulted or unknown calibration keys) to `reporter`.
DisplayDescription loadDisplay(const std::string& pathOrPreset, Reporter& reporter);
// A barrier display ("" the built-in), designed; a lenticular calibration is refused.
DisplayDesign loadBarrierDesign(const std::string& path, Reporter& reporter);

}  // namespace parallax::jobs
