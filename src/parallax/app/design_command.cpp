// `parallax design`: the derived barrier design of a display (G1-G4).
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
  std::printf("views                %.6g%s\n", d.views, s.subpixelRays ? " x 3 subpixel rays" : "");
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

}  // namespace

void registerDesignCommand(CLI::App& cli) {
  struct Options {
    std::string display, scene;
    FramingOptions framing;
    bool json = false;
    double depth = 0.0;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = cli.add_subcommand("design", "Print the derived barrier design of a display");
  cmd->add_option("display", options->display, "Display file (built-in display if omitted)");
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
    const DisplayDesign d = loadDesignOrDefault(options->display);
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
