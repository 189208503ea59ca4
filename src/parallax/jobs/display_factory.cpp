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
  refuseLensReading(camera.lensSpot, camera.bundles);
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
  const std::optional<LensOptics> optics = lensReading(design, camera.lensSpot, camera.bundles);
  return optics ? withOptics(design, *optics) : design;
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

std::optional<LensOptics> lensReading(const LenticularDesign& design,
                                      const std::optional<double>& lensSpot,
                                      const std::string& bundles) {
  if (!lensSpot && bundles.empty()) return std::nullopt;
  LensOptics optics = design.optics;
  if (lensSpot) {
    optics.spotWidthSubpixels = *lensSpot;
    const std::string problem = lensOpticsProblem(optics);
    if (!problem.empty()) throw RequestError("lens_spot", problem);
  }
  if (!bundles.empty() && !parseLensBundles(bundles, optics.bundles))
    throw RequestError("bundles", "expected parallel or converging", bundles);
  return optics;
}

void refuseLensReading(const std::optional<double>& lensSpot, const std::string& bundles) {
  if (lensSpot || !bundles.empty())
    throw RequestError(lensSpot ? "lens_spot" : "bundles",
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

DisplayDesign barrierDesignOf(const DisplayDescription& description) {
  if (description.kind != DisplayKind::Barrier)
    throw InputError(description.source(), "",
                     "is a lenticular calibration; this command takes a barrier display");
  return designDisplay(description.barrier, description.camera);
}

void checkFramingApplies(const DisplayDescription& /*description*/, const FramingRequest& framing) {
  framing.check();  // every kind frames: a barrier by its virtual gap, a lens by a depth scale
}

BuiltDisplay makeFramedDisplay(const DisplayDescription& description,
                               const DisplayCameraRequest& camera, const FramingRequest& framing,
                               Scene& scene) {
  checkFramingApplies(description, framing);
  framing.apply(scene.display);
  if (description.kind == DisplayKind::Lenticular) {
    const LenticularDesign design = lenticularDesign(description, camera);
    const Framing framed = frameForDisplay(scene, design);
    scene.display = framed.placement;
    BuiltDisplay built = lenticularDisplay(design, camera.filter);
    built.model = scaleDisplayedDepth(std::move(built.model), framed.depthScale);
    built.framing = framed;
    return built;
  }
  const Framing framed = frameForDisplay(scene, barrierDesign(description, camera));
  scene.display = framed.placement;
  BuiltDisplay built = barrierDisplay(framed.design, camera.filter);
  built.framing = framed;
  return built;
}

void BuiltDisplay::recordDesign(JsonWriter& record, const std::string& at) const {
  writeDisplayDesignJson(record, at, *model);
}

DisplayDescription loadDisplay(const std::string& pathOrPreset, Reporter& reporter) {
  DisplayDescription description = loadDisplayDescription(pathOrPreset);
  for (const std::string& warning : description.lenticular.warnings) reporter.warning(warning);
  return description;
}

DisplayDesign loadBarrierDesign(const std::string& path, Reporter& reporter) {
  return barrierDesignOf(loadDisplay(path, reporter));
}

}  // namespace parallax::jobs
