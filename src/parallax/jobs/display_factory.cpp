#include "parallax/jobs/display_factory.h"

#include <cmath>

#include "parallax/core/error.h"
#include "parallax/io/lenticular_file.h"

namespace parallax::jobs {

namespace {

DisplayDesign barrierDesign(const DisplayDescription& description,
                            const DisplayCameraRequest& camera) {
  if (camera.viewDistanceMm != 0)  // NaN too
    throw RequestError("distance",
                       "applies to lenticular displays; a barrier's view distance is its "
                       "design's (view_distance_mm in the display file)");
  BarrierCameraSettings settings = description.camera;
  settings.subpixelRays = settings.subpixelRays || camera.subpixels;
  return designDisplay(description.barrier, settings);
}

LenticularDesign lenticularDesign(const DisplayDescription& description,
                                  const DisplayCameraRequest& camera) {
  if (camera.subpixels)
    throw RequestError("subpixels",
                       "applies to barrier displays; a lenticular render always traces one ray "
                       "per subpixel");
  if (!(camera.viewDistanceMm >= 0 && std::isfinite(camera.viewDistanceMm)))
    throw RequestError("distance", "must be 0 (the calibration's own) or a distance in mm");
  return designLenticular(description.lenticular, camera.viewDistanceMm);
}

BuiltDisplay barrierDisplay(const DisplayDesign& design, const ViewFilter& filter) {
  BuiltDisplay built;
  built.model = makeBarrierDisplay(design, filter);
  built.file = {"display.json", displayFileText(design.spec, design.camera), "display"};
  return built;
}

BuiltDisplay lenticularDisplay(const LenticularDesign& design, const ViewFilter& filter) {
  BuiltDisplay built;
  built.model = makeLenticularDisplay(design, filter);
  built.file = {"visual.json", lenticularCalibrationText(design.calibration), "calibration"};
  return built;
}

}  // namespace

BuiltDisplay makeDisplay(const DisplayDescription& description,
                         const DisplayCameraRequest& camera) {
  switch (description.kind) {
    case DisplayKind::Barrier:
      return barrierDisplay(barrierDesign(description, camera), camera.filter);
    case DisplayKind::Lenticular:
      return lenticularDisplay(lenticularDesign(description, camera), camera.filter);
  }
  throw std::logic_error("unknown display kind");
}

DisplayDesign barrierDesignOf(const DisplayDescription& description) {
  if (description.kind != DisplayKind::Barrier)
    throw InputError(description.source(), "",
                     "is a lenticular calibration; this command takes a barrier display");
  return designDisplay(description.barrier, description.camera);
}

void checkFramingApplies(const DisplayDescription& description, const FramingRequest& framing) {
  framing.check();
  if (description.kind != DisplayKind::Barrier && framing.given())
    throw RequestError("framing",
                       "apply to barrier displays (their depth budget is the virtual gap)");
}

BuiltDisplay makeFramedDisplay(const DisplayDescription& description,
                               const DisplayCameraRequest& camera, const FramingRequest& framing,
                               Scene& scene) {
  checkFramingApplies(description, framing);
  if (description.kind != DisplayKind::Barrier) return makeDisplay(description, camera);
  framing.apply(scene.display);
  const Framing framed = frameForDisplay(scene, barrierDesign(description, camera));
  scene.display = framed.placement;
  BuiltDisplay built = barrierDisplay(framed.design, camera.filter);
  built.framing = framed;
  return built;
}

void BuiltDisplay::recordDesign(JsonWriter& record, const std::string& at) const {
  if (const DisplayDesign* barrier = model->barrierDesign()) writeDesignJson(record, at, *barrier);
  if (const LenticularDesign* lenticular = model->lenticularDesign())
    writeLenticularDesignJson(record, at, *lenticular);
}

}  // namespace parallax::jobs
