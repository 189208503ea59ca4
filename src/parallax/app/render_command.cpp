// `parallax render`: the display's pictures (jobs/render_job.h): options -> RenderRequest ->
// jobs::runRender, printed by the command line's reporter.
#include <CLI/CLI.hpp>

#include <memory>
#include <string>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"
#include "parallax/jobs/render_job.h"
#include "parallax/render/quilt.h"

namespace parallax::app {

namespace {

// The request, and the two options the command line spells as text: --quilt CxR|auto and
// --size WxH.
struct RenderOptions {
  RenderRequest request;
  std::string quilt, size;
};

void runRender(RenderOptions o) {
  RenderRequest& r = o.request;
  r.scene.load.import = importOptions();
  if (!o.quilt.empty()) {
    r.quilt.wanted = true;
    if (o.quilt != "auto" && !parseColumnsByRows(o.quilt, r.quilt.columns, r.quilt.rows))
      throw InputError("command line", "--quilt",
                       "expected COLUMNSxROWS or auto, got '" + o.quilt + "'");
    if (!o.size.empty()) parseSize("--size", o.size, r.quilt.width, r.quilt.height);
  } else if (!o.size.empty()) {
    r.quilt.width = r.quilt.height = 1;  // refused by the runner: --size needs --quilt
  }
  jobs::runRender(r, cliReporter());
}

}  // namespace

void registerRenderCommand(CLI::App& cli) {
  auto options = std::make_shared<RenderOptions>();
  RenderRequest& request = options->request;
  CLI::App* cmd =
      cli.add_subcommand("render", "Render the image and mask layers of a parallax display");
  CLI::Option* sceneOption = cmd->add_option("scene", request.scene.path,
                                             "Scene or mesh file (built-in scene if omitted)");
  addRgbdOptions(*cmd, request.scene.rgbd)->excludes(sceneOption);
  addSceneLoadOptions(*cmd, request.scene.load);
  cmd->add_option("--display", request.display,
                  "Display: a barrier display file, a lenticular calibration (visual.json), or a "
                  "Looking Glass preset lkg:NAME (built-in barrier display if omitted)");
  addSamplingOptions(*cmd, request.sampling,
                     "Rays per pixel: n*n stratified over pixel and aperture");
  addFilterOptions(
      *cmd, request.filter, "",
      "one view: a pixel column's angle at the gap; on a lenticular panel, the lens's focal "
      "spot");
  addFramingOptions(*cmd, request.framing, "");
  cmd->add_option("-o,--output", request.output, "Output folder")->capture_default_str();
  addLensReadingOptions(*cmd, request.lensSpot, request.bundles, true);
  cmd->add_flag("--linear", request.linear, "Also write image.pfm, linear float");
  CLI::Option* direct =
      cmd->add_flag("--direct-mapping", request.directMapping,
                    "The usual practice as a baseline: N ordinary views, interleaved (Fig. 2)");
  CLI::Option* subpixels = cmd->add_flag("--subpixels", request.subpixels,
                                         "One ray per R, G, B subpixel (three times the views)");
  cmd->add_option("--quilt", options->quilt,
                  "Instead of the layers: C*R off-axis views of the display's window, leftmost "
                  "camera first, as DIR/quilt_qs{C}x{R}a{aspect}.png (docs/quilts.md); auto: a "
                  "Looking Glass device's own quilt, or one row of a barrier's views")
      ->type_name("CxR|auto")
      ->excludes(direct)
      ->excludes(subpixels);
  cmd->add_option("--layers", request.layers.method,
                  "slits: the paper's slit mask and ray-traced image; optimized-image: the image "
                  "layer solved for eyes across the view zone behind the same slits; nmf: both "
                  "layers solved (docs/content-adaptive.md)")
      ->capture_default_str();
  cmd->add_option("--rank", request.layers.rank,
                  "With --layers nmf: time-multiplexed frame pairs (image-K.png, mask-K.png)")
      ->capture_default_str();
  // Through a function: the request tells a given --iterations from the default.
  cmd->add_option_function<int>(
         "--iterations", [&request](const int& n) { request.layers.iterations = n; },
         "With --layers optimized-image or nmf: solver iterations, 1 to 1000 (default 7)")
      ->type_name("INT");
  cmd->add_option("--brightness", request.layers.brightness,
                  "Brightness the optimised layers aim at, times the slits' (default 1 for "
                  "optimized-image, 1.05 max(2, rank) for nmf)");
  cmd->add_option("--layer-error", request.layers.error,
                  "The optimised image layer's error: srgb (on sRGB values, as the dense "
                  "measure's PSNR; its default) or linear (light; nmf's only)");
  cmd->add_option("--diffuser", request.layers.diffuser,
                  "With --layers optimized-image or nmf: the panel's diffuser foil, a Gaussian "
                  "blur of the rear layer (sigma in mm, as simulate --diffuser): the layers are "
                  "solved for what eyes see through it (default: the display file's "
                  "diffuser_sigma_mm, else none; docs/content-adaptive.md)")
      ->type_name("MM");
  cmd->add_flag("--color-filters", request.layers.colorFilters,
                "With --layers optimized-image or nmf: solve for what eyes see through the panels' "
                "colour filters (as simulate --color-filters: one channel a stripe of an RGB or "
                "BGR panel; docs/content-adaptive.md)");
  CLI::Option* pupil =
      cmd->add_option("--pupil", request.layers.pupil,
                      "With --layers optimized-image or nmf: solve for eyes with a pupil of this "
                      "diameter in mm (0 to 100; as simulate --pupil), each view the average "
                      "over --pupil-samples points of it (default 0: pinhole eyes)")
          ->type_name("MM");
  cmd->add_option("--pupil-samples", request.layers.pupilSamples,
                  "Points averaged over the --pupil, 1 to 64 (the solve's time grows with them)")
      ->capture_default_str()
      ->needs(pupil);
  cmd->add_option("--train-eyes", request.layers.trainEyes,
                  "Training eyes per view at each --train-distances for optimised layers")
      ->capture_default_str();
  cmd->add_option("--train-distances", request.layers.trainDistances,
                  "The training eyes' distances in units of the design distance D, separated by "
                  "commas (0.85,1.2: two thirds of the eyes and of the time, the dense measure "
                  "within 0.01 dB mean; docs/content-adaptive.md, \"Training eyes\")")
      ->capture_default_str();
  cmd->add_option("--train-spp", request.layers.trainSpp,
                  "Samples per pixel of the training eyes' ideal views for optimised layers, 1 "
                  "to 64 (default 2; each eye jittered on its own; docs/content-adaptive.md, "
                  "\"The targets' samples\")")
      ->type_name("N");
  cmd->add_option("--size", options->size,
                  "With --quilt: the size of one view (default: the device quilt's tile, or the "
                  "image layer's resolution)")
      ->type_name("WxH");
  addSequenceOptions(*cmd, request.sequence,
                     "the frames' image layers (with --quilt: their quilts)");
  cmd->callback([options] { runRender(*options); });
}

}  // namespace parallax::app
