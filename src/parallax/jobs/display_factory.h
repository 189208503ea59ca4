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
#include "parallax/jobs/display_request.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/requests.h"
#include "parallax/scene/scene.h"

namespace parallax::jobs {

// The lenticular optics that a lens reading asks for, over the design's own; unset when none is
// given. Throws RequestError naming lens_spot (outside 0 to 12 subpixels) or bundles (neither
// parallel nor converging).
std::optional<LensOptics> lensReading(const LenticularDesign& design,
                                      const LensReadingRequest& lens);
// A barrier has no lenses: throws RequestError naming lens_spot or bundles when either is given.
void refuseLensReading(const LensReadingRequest& lens);

// A display built for a camera, and what a render writes beside its pictures.
struct BuiltDisplay {
  std::unique_ptr<DisplayModel> model;
  // The display as its file (display.json, or a calibration's visual.json), for output sets.
  DisplayFile file;
  ViewFilter filter;               // the camera's, kept for a design the framing changes
  std::optional<Framing> framing;  // how the scene was framed for it (frameDisplay)
  // Every given and derived figure of its design under the JSON pointer `at`.
  void recordDesign(JsonWriter& record, const std::string& at) const;

  const DisplayModel& operator*() const { return *model; }
  const DisplayModel* operator->() const { return model.get(); }
};

// A barrier's design (with the file's camera settings); a lenticular calibration is refused,
// naming the file, for the commands that take barriers only.
DisplayDesign barrierDesignOf(const DisplayDescription& description);

// Designs the display: the one design a description gets. Throws RequestError for a choice its
// kind does not have (subpixels on a lenticular panel, a viewer distance on a barrier, whose
// distance is its design's).
BuiltDisplay makeDisplay(const DisplayDescription& description,
                         const DisplayCameraRequest& camera = {});

// The display a request names, designed for the camera (with `filter`): its description's
// (`described`: request.describe(), read before the request's other refusals), or the one made
// in code (DisplayRequest::madeInCode), which has no file.
BuiltDisplay buildDisplay(const DisplayRequest& request, const DisplayDescription& described,
                          const ViewFilter& filter = {});

// The display framing `scene` for itself (camera/framing.h: the placement's width, the
// zero-parallax plane, and for the depth budget a barrier's virtual gap or a lenticular panel's
// depth scale, display/depth_scaled_display.h); `scene`'s placement becomes the framing's. The
// display is designed again only when the framing gives a barrier a virtual gap of its own.
BuiltDisplay frameDisplay(BuiltDisplay display, const FramingRequest& framing, Scene& scene);
// makeDisplay, then frameDisplay.
BuiltDisplay makeFramedDisplay(const DisplayDescription& description,
                               const DisplayCameraRequest& camera, const FramingRequest& framing,
                               Scene& scene);

// A barrier display ("" the built-in), designed; a lenticular calibration is refused.
DisplayDesign loadBarrierDesign(const std::string& path, Reporter& reporter);

}  // namespace parallax::jobs
