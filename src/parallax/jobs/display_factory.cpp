#include "parallax/jobs/display_factory.h"

#include <cmath>

#include "parallax/core/error.h"
#include "parallax/display/depth_scaled_display.h"
#include "parallax/io/lenticular_file.h"

namespace parallax::jobs {

namespace {

DisplayDesign barrierDesign(const DisplayDescription& description,
                            const DisplayCameraRequest& camera) {
  if (camera.viewDistanceMm != 0)  // NaN too
    throw RequestError("distance",
                       "applies to lenticular displays; a barrier's view distance is its "
                       "design's (view_distance_mm in the display file)");
  refuseLensReading(camera.lens);
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
  const LenticularDesign design = designLenticular(description.lenticular, camera.viewDistanceMm);
  const std::optional<LensOptics> optics = lensReading(design, camera.lens);
  return optics ? withOptics(design, *optics) : design;
}

BuiltDisplay barrierDisplay(const DisplayDesign& design, const ViewFilter& filter) {
  BuiltDisplay built;
  built.model = makeBarrierDisplay(design, filter);
  built.filter = filter;
  built.file = {"display.json", displayFileText(design.spec, design.camera), "display"};
  return built;
}

BuiltDisplay lenticularDisplay(const LenticularDesign& design, const ViewFilter& filter) {
  BuiltDisplay built;
  built.model = makeLenticularDisplay(design, filter);
  built.filter = filter;
  built.file = {"visual.json", lenticularCalibrationText(design.calibration), "calibration"};
  return built;
}

}  // namespace

std::optional<LensOptics> lensReading(const LenticularDesign& design,
                                      const LensReadingRequest& lens) {
  if (!lens.given()) return std::nullopt;
  LensOptics optics = design.optics;
  if (lens.spot) {
    optics.spotWidthSubpixels = *lens.spot;
    const std::string problem = lensOpticsProblem(optics);
    if (!problem.empty()) throw RequestError("lens_spot", problem);
  }
  if (!lens.bundles.empty() && !parseLensBundles(lens.bundles, optics.bundles))
    throw RequestError("bundles", "expected parallel or converging", lens.bundles);
  return optics;
}

void refuseLensReading(const LensReadingRequest& lens) {
  if (lens.given())
    throw RequestError(lens.spot ? "lens_spot" : "bundles",
                       "applies to lenticular displays (the lenses' optics); a barrier display "
                       "has no lenses");
}

BuiltDisplay makeDisplay(const DisplayDescription& description,
                         const DisplayCameraRequest& camera) {
  switch (description.kind) {
    case DisplayKind::Barrier:
      return barrierDisplay(barrierDesign(description, camera), camera.filter);
    case DisplayKind::Lenticular:
      return lenticularDisplay(lenticularDesign(description, camera), camera.filter);
    case DisplayKind::Other:  // made in code, never read from a file
      break;
  }
  throw std::logic_error("makeDisplay: a description of a kind without a file");
}

BuiltDisplay buildDisplay(const DisplayRequest& request, const DisplayDescription& described,
                          const ViewFilter& filter) {
  if (!request.madeInCode) return makeDisplay(described, request.camera(filter));
  BuiltDisplay built;
  built.model = request.madeInCode(request.camera(filter));
  built.filter = filter;
  return built;
}

DisplayDesign barrierDesignOf(const DisplayDescription& description) {
  if (description.kind != DisplayKind::Barrier)
    throw InputError(description.source(), "",
                     "is a lenticular calibration; this command takes a barrier display");
  return designDisplay(description.barrier, description.camera);
}

BuiltDisplay frameDisplay(BuiltDisplay display, const FramingRequest& framing, Scene& scene) {
  framing.check();  // every kind frames: a barrier by its virtual gap, a lens by a depth scale
  framing.apply(scene.display);
  const Framing framed = frameForDisplay(scene, *display.model);
  scene.display = framed.placement;
  if (const DisplayDesign* barrier = display->barrierDesign()) {
    // A barrier shows depth through its virtual gap g' (geometry.md, "Physical display vs
    // virtual camera"): the framing's design when the depth budget chose one.
    if (framed.design.virtualGapMm != barrier->virtualGapMm)
      display = barrierDisplay(framed.design, display.filter);
  } else {
    display.model = scaleDisplayedDepth(std::move(display.model), framed.depthScale);
  }
  display.framing = framed;
  return display;
}

BuiltDisplay makeFramedDisplay(const DisplayDescription& description,
                               const DisplayCameraRequest& camera, const FramingRequest& framing,
                               Scene& scene) {
  return frameDisplay(makeDisplay(description, camera), framing, scene);
}

void BuiltDisplay::recordDesign(JsonWriter& record, const std::string& at) const {
  writeDisplayDesignJson(record, at, *model);
}

DisplayDesign loadBarrierDesign(const std::string& path, Reporter& reporter) {
  return barrierDesignOf(loadDisplay(path, reporter));
}

}  // namespace parallax::jobs
