// lenticular simulate: what an eye sees of a panel picture through a lens sheet (the lenticular
// panel's own command; interlace_job.h declares it).
#include <cstdio>

#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/core/output_path.h"
#include "parallax/io/image_file.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/interlace_job.h"
#include "parallax/jobs/limits.h"
#include "parallax/sim/lenticular_sim.h"

namespace parallax::jobs {

namespace {

// The panel's design (at the request's viewer distance), its pictures checked against memory.
LenticularDesign simulatedPanel(const LenticularSimulateRequest& r, Reporter& reporter) {
  const DisplayDescription description = r.display.describe(reporter);
  if (!makeDisplay(description)->lenticularDesign())
    throw InputError(description.source(), "",
                     "is a barrier display, not a lenticular calibration (visual.json, lkg:NAME)");
  const LenticularDesign design = *makeDisplay(description, r.display.camera())->lenticularDesign();
  const double w = design.calibration.screenW, h = design.calibration.screenH;
  checkMemoryEstimate(imageBytes(w, h, kFloatRgbPixelBytes, 2) + imageBytes(w, h, kRgba8PixelBytes),
                      r.display.loaded ? description.source() : r.display.path,
                      "the panel and the view", "use a smaller panel");
  return design;
}

Vec3d simulatedEye(const LenticularSimulateRequest& r, const LenticularDesign& design) {
  if (!r.eye) return {0, 0, design.viewDistanceMm};
  if (!(r.eye->z > 0)) throw RequestError("eye", "the eye must be in front (z > 0)");
  return *r.eye;
}

}  // namespace

void runLenticularSimulate(const LenticularSimulateRequest& r, Reporter& reporter) {
  const LenticularDesign design = simulatedPanel(r, reporter);
  checkOutputFile(r.output);
  const Image panel = readImage(r.image);
  const Vec3d eye = simulatedEye(r, design);
  const Image view = simulateLenticularView(design, panel, eye);
  writeImage(r.output, view);
  reporter.result(printed("wrote %s (%dx%d): the panel seen from %.1f,%.1f,%.1f mm",
                          r.output.c_str(), view.width(), view.height(), eye.x, eye.y, eye.z));
}

Image lenticularViewInMemory(const LenticularSimulateRequest& r, const Image& panel,
                             Reporter& reporter) {
  const LenticularDesign design = simulatedPanel(r, reporter);
  return simulateLenticularView(design, panel, simulatedEye(r, design));
}

}  // namespace parallax::jobs
