// `parallax render`: the display's pictures (jobs/render_job.h): options -> RenderRequest ->
// jobs::runRender, printed by the command line's reporter.
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

void registerRenderCommand(Command& cli) {
  auto options = std::make_shared<RenderOptions>();
  RenderRequest& request = options->request;
  Command* cmd =
      cli.addSubcommand("render", "Render the image and mask layers of a parallax display");
  Option* sceneOption =
      cmd->addOption("scene", request.scene.path, "Scene or mesh file (built-in scene if omitted)");
  addRgbdOptions(*cmd, request.scene.rgbd)->excludes(sceneOption);
  addSceneLoadOptions(*cmd, request.scene.load);
  addDisplayOption(*cmd, request.display,
                   "Display: a barrier display file, a lenticular calibration (visual.json), or a "
                   "Looking Glass preset lkg:NAME (built-in barrier display if omitted)");
  addSamplingOptions(*cmd, request.sampling,
                     "Rays per pixel: n*n stratified over pixel and aperture");
  addFilterOptions(
      *cmd, request.filter, "",
      "one view: a pixel column's angle at the gap; on a lenticular panel, the lens's focal "
      "spot");
  addFramingOptions(*cmd, request.framing, "");
  cmd->addOption("-o,--output", request.output, "Output folder")->captureDefault();
  addLensReadingOptions(*cmd, request.display.lens, true);
  cmd->addFlag("--linear", request.linear, "Also write image.pfm, linear float");
  Option* direct =
      cmd->addFlag("--direct-mapping", request.directMapping,
                   "The usual practice as a baseline: N ordinary views, interleaved (Fig. 2)");
  Option* subpixels = cmd->addFlag("--subpixels", request.display.subpixels,
                                   "One ray per R, G, B subpixel (three times the views)");
  cmd->addOption("--quilt", options->quilt,
                 "Instead of the layers: C*R off-axis views of the display's window, leftmost "
                 "camera first, as DIR/quilt_qs{C}x{R}a{aspect}.png (docs/quilts.md); auto: a "
                 "Looking Glass device's own quilt, or one row of a barrier's views")
      ->typeName("CxR|auto")
      ->excludes(direct)
      ->excludes(subpixels);
  cmd->addOption("--layers", request.layers.method,
                 "slits: the paper's slit mask and ray-traced image; optimized-image: the image "
                 "layer solved for eyes across the view zone behind the same slits; nmf: both "
                 "layers solved (docs/content-adaptive.md)")
      ->captureDefault();
  cmd->addOption("--rank", request.layers.rank,
                 "With --layers nmf: time-multiplexed frame pairs (image-K.png, mask-K.png)")
      ->captureDefault();
  // Through a function: the request tells a given --iterations from the default.
  cmd->addOptionFunction<int>(
         "--iterations", [&request](const int& n) { request.layers.iterations = n; },
         "With --layers optimized-image or nmf: solver iterations, 1 to 1000 (default 7)")
      ->typeName("INT");
  cmd->addOption("--brightness", request.layers.brightness,
                 "Brightness the optimised layers aim at, times the slits' (default 1 for "
                 "optimized-image, 1.05 max(2, rank) for nmf)");
  cmd->addOption("--layer-error", request.layers.error,
                 "The optimised image layer's error: srgb (on sRGB values, as the dense "
                 "measure's PSNR; its default) or linear (light; nmf's only)");
  cmd->addOption("--diffuser", request.layers.diffuser,
                 "With --layers optimized-image or nmf: the panel's diffuser foil, a Gaussian "
                 "blur of the rear layer (sigma in mm, as simulate --diffuser): the layers are "
                 "solved for what eyes see through it (default: the display file's "
                 "diffuser_sigma_mm, else none; docs/content-adaptive.md)")
      ->typeName("MM");
  cmd->addFlag("--color-filters", request.layers.colorFilters,
               "With --layers optimized-image or nmf: solve for what eyes see through the panels' "
               "colour filters (as simulate --color-filters: one channel a stripe of an RGB or "
               "BGR panel; docs/content-adaptive.md)");
  Option* pupil =
      cmd->addOption("--pupil", request.layers.pupil,
                     "With --layers optimized-image or nmf: solve for eyes with a pupil of this "
                     "diameter in mm (0 to 100; as simulate --pupil), each view the average "
                     "over --pupil-samples points of it (default 0: pinhole eyes)")
          ->typeName("MM");
  cmd->addOption("--pupil-samples", request.layers.pupilSamples,
                 "Points averaged over the --pupil, 1 to 64 (the solve's time grows with them)")
      ->captureDefault()
      ->needs(pupil);
  cmd->addOption("--train-eyes", request.layers.trainEyes,
                 "Training eyes per view at each --train-distances for optimised layers")
      ->captureDefault();
  cmd->addOption("--train-distances", request.layers.trainDistances,
                 "The training eyes' distances in units of the design distance D, separated by "
                 "commas (0.85,1.2: two thirds of the eyes and of the time, the dense measure "
                 "within 0.01 dB mean; docs/content-adaptive.md, \"Training eyes\")")
      ->captureDefault();
  cmd->addOption("--train-spp", request.layers.trainSpp,
                 "Samples per pixel of the training eyes' ideal views for optimised layers, 1 "
                 "to 64 (default 2; each eye jittered on its own; docs/content-adaptive.md, "
                 "\"The targets' samples\")")
      ->typeName("N");
  cmd->addOption("--size", options->size,
                 "With --quilt: the size of one view (default: the device quilt's tile, or the "
                 "image layer's resolution)")
      ->typeName("WxH");
  addSequenceOptions(*cmd, request.sequence,
                     "the frames' image layers (with --quilt: their quilts)");
  cmd->callback([options] { runRender(*options); });
}

}  // namespace parallax::app
