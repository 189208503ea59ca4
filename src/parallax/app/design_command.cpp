// `parallax design`: the derived design of a display: a barrier's (G1-G4), a lenticular's.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/camera/framing.h"
#include "parallax/core/error.h"
#include "parallax/io/display_file.h"
#include "parallax/io/lenticular_file.h"

namespace parallax::app {

namespace {

void printDesign(const DisplayDesign& d, double depthMm) {
  const auto& s = d.spec;
  const bool back = s.order == LayerOrder::BarrierBack;
  std::printf("display              %s (%s: %s layer in front)\n", s.source.c_str(),
              back ? "barrier-back" : "barrier-front", back ? "image" : "mask");
  std::printf("image layer          %dx%d px, %.4f mm pixels\n", s.imagePanel.width,
              s.imagePanel.height, s.imagePanel.pitchMm);
  std::printf("mask layer           %dx%d px, %.4f mm pixels\n", s.maskPanel.width,
              s.maskPanel.height, s.maskPanel.pitchMm);
  std::printf("gap g                %.4g mm\n", d.gapMm);
  std::printf("view distance D      %.6g mm\n", d.viewDistanceMm);
  std::printf("screen period Tx     %.6g mm = %.6g px\n", d.screenPeriodMm, d.screenPeriodPx);
  std::printf("slit period Tv       %.6g mm = %.6g mask px\n", d.slitPeriodMm, d.slitPeriodPx);
  std::printf("views                %.6g%s\n", d.views,
              d.camera.subpixelRays ? " x 3 subpixel rays" : "");
  std::printf("apertures            %.0f across", d.aperturesAcross);
  if (s.mask.kind == MaskKind::Pinholes) std::printf(", %.0f down", d.aperturesDown);
  std::printf("\nview zone width S    %.5g mm (%.4g mm per view) at D\n", d.viewZoneWidthMm,
              d.viewWidthMm);
  std::printf("depth of field       +-%.4g mm around the aperture plane (G4)\n", d.depthOfFieldMm);
  if (std::isinf(d.farthestConsistentDistanceMm))
    std::printf("farthest consistent  unbounded (apertures span less than S)\n");
  else
    std::printf("farthest consistent  %.6g mm (the paper's D S / (Sv - S))\n",
                d.farthestConsistentDistanceMm);
  std::printf("disparity            %.4g mm between adjacent views at depth %g mm\n",
              d.adjacentViewDisparityMm(depthMm), depthMm);
}

// A lenticular calibration's design: the lens figures and the design viewer.
void printLenticularDesign(const LenticularDesign& d, bool json) {
  if (json) {
    JsonWriter out;
    out.set("/kind", "lenticular");
    writeLenticularDesignJson(out, "", d);
    std::printf("%s\n", out.dump().c_str());
    return;
  }
  const LenticularCalibration& c = d.calibration;
  std::printf("display              %s (slanted lenticular, %dx%d px, %.4g DPI)\n",
              c.source.c_str(), c.screenW, c.screenH, c.dpi);
  std::printf("panel                %.1f x %.1f mm, %.4f mm pixels\n", d.widthMm, d.heightMm,
              d.pixelPitchMm);
  std::printf("lenses               %.4g per inch, %.4f mm pitch, slant %.2f deg from vertical\n",
              c.pitch, d.lensPitchMm, d.lensSlantDegrees);
  std::printf("pixels per lens      %.4g along a row (%.4g subpixels)\n", d.pixelsPerLens,
              d.subpixelsPerLens);
  std::printf("view cone            %.4g deg, %s\n", c.viewConeDegrees,
              c.invView ? "inverted (invView)" : "not inverted");
  std::printf("subpixels            %s\n",
              c.subpixelCells.empty()
                  ? (c.flipSubpixels ? "BGR stripes" : "RGB stripes")
                  : ("cells, pattern " + std::to_string(c.cellPatternMode)).c_str());
  std::printf("design viewer        %.0f mm away, the cone %.0f mm wide there\n", d.viewDistanceMm,
              d.viewZoneWidthMm);
  std::printf("default quilt        %dx%d views, %dx%d px\n", c.quilt.columns, c.quilt.rows,
              c.quilt.width, c.quilt.height);
}

}  // namespace

void registerDesignCommand(CLI::App& cli) {
  struct Options {
    std::string display, scene;
    FramingOptions framing;
    bool json = false;
    double depth = 0.0;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd =
      cli.add_subcommand("design", "Print the derived design of a display (barrier or lenticular)");
  cmd->add_option("display", options->display,
                  "Display file of any kind, or lkg:NAME (built-in display if omitted)");
  cmd->add_option("--depth", options->depth,
                  "Depth (mm, + toward the viewer) for the disparity figure; default: the depth "
                  "of field")
      ->check(realIn(-kInfinity, kInfinity));
  cmd->add_flag("--json", options->json, "Print one JSON object");
  cmd->add_option("--scene", options->scene,
                  "Also frame this scene for the display as render does: its depth range "
                  "against the depth of field");
  addFramingOptions(*cmd, options->framing, "With --scene: ");
  cmd->callback([options] {
    const DisplayDescription description = loadDisplayOrDefault(options->display);
    if (description.kind == DisplayKind::Lenticular) {
      if (!options->scene.empty() || options->framing.given())
        throw InputError("command line", "--scene",
                         "frames a scene for a barrier display's depth of field");
      return printLenticularDesign(designLenticular(description.lenticular), options->json);
    }
    const DisplayDesign d = designDisplay(description.barrier, description.camera);
    std::optional<Framing> framing;
    if (!options->scene.empty()) {
      Scene scene = loadSceneOrDefault(options->scene);
      options->framing.apply(scene.display);
      framing = frameForDisplay(scene, d);
    } else if (options->framing.given()) {
      throw InputError("command line", "--fit", "--fit, --focus and --depth-budget need --scene");
    }
    const double depth = options->depth != 0.0 ? options->depth : d.depthOfFieldMm;
    if (!(std::abs(depth) < d.viewDistanceMm))
      throw InputError("command line", "--depth", "must lie between the viewer and -D");
    if (!options->json) {
      printDesign(d, depth);
      if (framing) {
        std::printf("%s\n", depthSummary(*framing).c_str());
        const std::string warning = depthWarning(*framing);
        if (!warning.empty()) std::printf("warning: %s\n", warning.c_str());
      }
      return;
    }
    JsonWriter json;
    writeDesignJson(json, "", d);
    json.set("/disparity_depth_mm", depth);
    json.set("/disparity_mm", d.adjacentViewDisparityMm(depth));
    if (framing) {
      const Framing& f = *framing;
      json.set("/scene/source", options->scene);
      setFramingFigures(json, "/scene", f);
    }
    std::printf("%s\n", json.dump().c_str());
  });
}

}  // namespace parallax::app
