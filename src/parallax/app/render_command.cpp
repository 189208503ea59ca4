// `parallax render`: the two layer images of the display, and a record of how they were made.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"
#include "parallax/io/display_file.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/render/display_render.h"

namespace parallax::app {

namespace {

struct RenderOptions {
  std::string scene, display;
  int spp = 16;
  int threads = 0;
  uint64_t seed = 0;
  std::string output = "out";
  bool linear = false;
  bool subpixels = false;
  bool directMapping = false;
};

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

void runRender(const RenderOptions& o) {
  if (o.spp < 1) throw InputError("command line", "--spp", "must be at least 1");
  DisplayDesign design = loadDesignOrDefault(o.display);
  if (o.subpixels) {
    DisplaySpec spec = design.spec;
    spec.subpixelRays = true;
    design = designDisplay(spec);
  }
  const Scene scene = loadSceneOrDefault(o.scene);
  for (const auto& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const Accelerator accelerator(scene);
  RenderSettings settings;
  settings.samplesPerPixel = o.spp;
  settings.threads = o.threads;
  settings.seed = o.seed;
  DisplayLayers layers;
  {
    ProgressBar bar("render");
    const auto onProgress = [&bar](int done, int total) { bar.update(done, total); };
    layers = o.directMapping ? renderDirectMapping(scene, accelerator, design, settings, onProgress)
                             : renderDisplay(scene, accelerator, design, settings, onProgress);
  }
  const double raysPerSecond = double(layers.stats.totalRays()) / layers.stats.seconds;

  JsonWriter record;
  record.set("/program", "parallax");
  record.set("/version", PARALLAX_VERSION);
  record.set("/created", utcNow());
  record.set("/scene", scene.source);
  record.set("/display_file", o.display.empty() ? std::string("<built-in>") : o.display);
  record.set("/spp", o.spp);
  record.set("/method", o.directMapping ? "direct-mapping" : "barrier-camera");
  record.set("/seed", o.seed);
  record.set("/threads", o.threads);
  record.set("/seconds", layers.stats.seconds);
  record.set("/rays", layers.stats.totalRays());
  record.set("/rays_per_second", raysPerSecond);
  record.set("/outputs/image", "image.png");
  record.set("/outputs/mask", "mask.png");
  record.set("/outputs/display", "display.json");
  record.set("/scene_display/center", scene.display.center);
  record.set("/scene_display/normal", scene.display.normal);
  record.set("/scene_display/up", scene.display.up);
  record.set("/scene_display/width", double(scene.display.width));
  writeDesignJson(record, "/design", design);
  if (o.linear) record.set("/outputs/image_linear", "image.pfm");

  const std::string dir = o.output.empty() ? "." : o.output;
  writeImage(dir + "/image.png", layers.image);
  writeImage(dir + "/mask.png", layers.mask);
  if (o.linear) writeImage(dir + "/image.pfm", layers.image);
  // The display as a display file, so that `simulate DIR` and other tools can read it back.
  writeFileAtomically(dir + "/display.json", displayFileText(design.spec));
  writeFileAtomically(dir + "/render.json", record.dump() + "\n");
  std::printf("wrote %s/image.png (%dx%d), %s/mask.png (%dx%d), %s/render.json\n", dir.c_str(),
              layers.image.width(), layers.image.height(), dir.c_str(), layers.mask.width(),
              layers.mask.height(), dir.c_str());
  std::printf("%d spp in %.2f s, %s\n", o.spp, layers.stats.seconds,
              formatRate(raysPerSecond).c_str());
}

}  // namespace

void registerRenderCommand(CLI::App& cli) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd =
      cli.add_subcommand("render", "Render the image and mask layers of a parallax display");
  cmd->add_option("scene", options->scene, "Scene or mesh file (built-in scene if omitted)");
  cmd->add_option("--display", options->display, "Display file (built-in display if omitted)");
  cmd->add_option("--spp", options->spp, "Rays per pixel: n*n stratified over pixel and aperture")
      ->capture_default_str();
  cmd->add_option("--threads", options->threads, "Worker threads (0: all cores)");
  cmd->add_option("--seed", options->seed, "Seed of the sample jitter");
  cmd->add_option("-o,--output", options->output, "Output folder")->capture_default_str();
  cmd->add_flag("--linear", options->linear, "Also write image.pfm, linear float");
  cmd->add_flag("--direct-mapping", options->directMapping,
                "The usual practice as a baseline: N ordinary views, interleaved (Fig. 2)");
  cmd->add_flag("--subpixels", options->subpixels,
                "One ray per R, G, B subpixel (three times the views)");
  cmd->callback([options] { runRender(*options); });
}

}  // namespace parallax::app
