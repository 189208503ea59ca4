#include "parallax/jobs/design_job.h"

#include <cmath>

#include "parallax/camera/framing.h"
#include "parallax/core/error.h"
#include "parallax/display/depth_scaled_display.h"
#include "parallax/io/json_writer.h"
#include "parallax/io/lenticular_file.h"
#include "parallax/jobs/display_factory.h"

namespace parallax::jobs {

namespace {

std::string barrierText(const DisplayDesign& d, double depthMm) {
  const auto& s = d.spec;
  const bool back = s.order == LayerOrder::BarrierBack;
  std::string text;
  text += printed("display              %s (%s: %s layer in front)\n", s.source.c_str(),
                  back ? "barrier-back" : "barrier-front", back ? "image" : "mask");
  text += printed("image layer          %dx%d px, %.4f mm pixels\n", s.imagePanel.width,
                  s.imagePanel.height, s.imagePanel.pitchMm);
  text += printed("mask layer           %dx%d px, %.4f mm pixels\n", s.maskPanel.width,
                  s.maskPanel.height, s.maskPanel.pitchMm);
  text += printed("gap g                %.4g mm\n", d.gapMm);
  text += printed("view distance D      %.6g mm\n", d.viewDistanceMm);
  text += printed("screen period Tx     %.6g mm = %.6g px\n", d.screenPeriodMm, d.screenPeriodPx);
  text += printed("slit period Tv       %.6g mm = %.6g mask px\n", d.slitPeriodMm, d.slitPeriodPx);
  text += printed("views                %.6g%s\n", d.views,
                  d.camera.subpixelRays ? " x 3 subpixel rays" : "");
  text += printed("apertures            %.0f across", d.aperturesAcross);
  if (s.mask.kind == MaskKind::Pinholes) text += printed(", %.0f down", d.aperturesDown);
  text += printed("\nview zone width S    %.5g mm (%.4g mm per view) at D\n", d.viewZoneWidthMm,
                  d.viewWidthMm);
  text +=
      printed("depth of field       +-%.4g mm around the aperture plane (G4)\n", d.depthOfFieldMm);
  if (std::isinf(d.farthestConsistentDistanceMm))
    text += "farthest consistent  unbounded (apertures span less than S)\n";
  else
    text += printed("farthest consistent  %.6g mm (the paper's D S / (Sv - S))\n",
                    d.farthestConsistentDistanceMm);
  text += printed("disparity            %.4g mm between adjacent views at depth %g mm\n",
                  d.adjacentViewDisparityMm(depthMm), depthMm);
  return text;
}

// A lenticular calibration's design: the lens figures and the design viewer.
std::string lenticularText(const LenticularDesign& d) {
  const LenticularCalibration& c = d.calibration;
  std::string text;
  text += printed("display              %s (slanted lenticular, %dx%d px, %.4g DPI)\n",
                  c.source.c_str(), c.screenW, c.screenH, c.dpi);
  text += printed("panel                %.1f x %.1f mm, %.4f mm pixels\n", d.widthMm, d.heightMm,
                  d.pixelPitchMm);
  text +=
      printed("lenses               %.4g per inch, %.4f mm pitch, slant %.2f deg from vertical\n",
              c.pitch, d.lensPitchMm, d.lensSlantDegrees);
  text += printed("pixels per lens      %.4g along a row (%.4g subpixels)\n", d.pixelsPerLens,
                  d.subpixelsPerLens);
  text += printed("view cone            %.4g deg, %s\n", c.viewConeDegrees,
                  c.invView ? "inverted (invView)" : "not inverted");
  text += printed("subpixels            %s\n",
                  c.subpixelCells.empty()
                      ? (c.flipSubpixels ? "BGR stripes" : "RGB stripes")
                      : ("cells, pattern " + std::to_string(c.cellPatternMode)).c_str());
  text += printed("design viewer        %.0f mm away, the cone %.0f mm wide there\n",
                  d.viewDistanceMm, d.viewZoneWidthMm);
  text += printed("default quilt        %dx%d views, %dx%d px\n", c.quilt.columns, c.quilt.rows,
                  c.quilt.width, c.quilt.height);
  // Which device a unit's own file is, which chose that quilt (display/lenticular_presets.h).
  if (!c.deviceBasis.empty())
    text += printed("device               lkg:%s, by its %s\n", c.device.c_str(),
                    c.deviceBasis.c_str());
  else if (c.device.empty())
    text += "device               none known: the quilt is derived from the panel\n";
  text += printed(
      "depth of field       +-%.4g mm around the panel (a point spreads over %g lens "
      "through a %g-subpixel window)\n",
      lensDepthOfFieldMm(d), kSharpLenses, lensWindowSubpixels(d.optics));
  return text;
}

}  // namespace

DesignReport designReport(const DesignRequest& r, Reporter& reporter, const Scene* given) {
  const BuiltDisplay display = buildDisplay(r.display, r.display.describe(reporter));
  DesignReport report;
  JsonWriter json;
  // The framing of the scene, as render frames it for this display.
  std::optional<Framing> framing;
  std::string sceneSource;
  if (r.scene) {
    Scene scene = given ? *given : loadSceneQuietly(*r.scene);
    sceneSource = given ? given->source : r.scene->path;
    r.framing.apply(scene.display);
    framing = frameForDisplay(scene, *display);
  } else if (r.framing.given()) {
    throw RequestError("fit", "{fit}, {focus} and {depth_budget} need {scene}");
  }
  const auto addFraming = [&] {
    if (!framing) return;
    report.text += depthSummary(*framing) + "\n";
    const std::string warning = depthWarning(*framing);
    if (!warning.empty()) report.text += "warning: " + warning + "\n";
    json.set("/scene/source", sceneSource);
    setFramingFigures(json, "/scene", *framing);
  };
  if (const LenticularDesign* lenticular = display->lenticularDesign()) {
    json.set("/kind", "lenticular");
    writeLenticularDesignJson(json, "", *lenticular);
    json.set("/depth_of_field_mm", lensDepthOfFieldMm(*lenticular));
    report.text = lenticularText(*lenticular);
    addFraming();
    report.json = json.dump();
    return report;
  }
  const DisplayDesign* barrier = display->barrierDesign();
  if (!barrier) {  // another kind: the figures its model reports
    json.set("/kind", displayKindName(display->kind()));
    report.text = printed("display              %s (%s)\n", display->source().c_str(),
                          displayKindName(display->kind()));
    for (const DesignFigure& f : display->designReport()) {
      json.set("/" + f.key, f.value);
      report.text += printed("%-20s %.6g%s%s\n", f.key.c_str(), f.value, f.unit.empty() ? "" : " ",
                             f.unit.c_str());
    }
    addFraming();
    report.json = json.dump();
    return report;
  }
  const DisplayDesign& d = *barrier;
  const double depth = r.depth != 0.0 ? r.depth : d.depthOfFieldMm;
  if (!(std::abs(depth) < d.viewDistanceMm))
    throw RequestError("depth", "must lie between the viewer and -D");
  report.text = barrierText(d, depth);
  writeDesignJson(json, "", d);
  json.set("/disparity_depth_mm", depth);
  json.set("/disparity_mm", d.adjacentViewDisparityMm(depth));
  addFraming();
  report.json = json.dump();
  return report;
}

}  // namespace parallax::jobs
