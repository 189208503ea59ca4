// `parallax lenticular`: slanted lenticular displays (the Looking Glass family) from their
// calibration file: render the panel's framebuffer, and see it from an eye (docs/lenticular.md).
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"
#include "parallax/jobs/interlace_job.h"
#include "parallax/jobs/render_job.h"

namespace parallax::app {

namespace {

namespace fs = std::filesystem;

struct LenticularSimulateOptions {
  std::vector<std::string> inputs;  // DIR [CALIBRATION], or CALIBRATION with --image
  std::string image, eye, output = "out/lenticular-view.png";
  DisplayRequest display;  // the calibration (from inputs), distance and the lens reading
};

// `lenticular render CALIBRATION`: `render --display CALIBRATION` with a viewer distance.
void runRender(RenderRequest r) {
  r.scene.load.import = importOptions();
  jobs::runRender(r, cliReporter());
}

void runSimulate(const LenticularSimulateOptions& o) {
  LenticularSimulateRequest r;
  r.display = o.display;
  r.image = o.image;
  if (!o.image.empty()) {
    if (o.inputs.size() != 1)
      throw InputError("command line", "--image", "takes the calibration file as the argument");
    r.display.path = o.inputs[0];
  } else {
    if (o.inputs.empty() || o.inputs.size() > 2)
      throw InputError("command line", "DIR",
                       "expected DIR [CALIBRATION] or --image FILE CALIBRATION");
    r.image = (fs::path(o.inputs[0]) / "image.png").string();
    r.display.path =
        o.inputs.size() == 2 ? o.inputs[1] : (fs::path(o.inputs[0]) / "visual.json").string();
  }
  if (!o.eye.empty()) {
    const Vec3f e = parseVec3("--eye", o.eye);
    r.eye = Vec3d{e.x, e.y, e.z};
  }
  r.output = o.output;
  jobs::runLenticularSimulate(r, cliReporter());
}

}  // namespace

void registerLenticularCommand(Command& cli) {
  Command* cmd = cli.addSubcommand(
      "lenticular", "Slanted lenticular displays (Looking Glass family) from their visual.json");
  cmd->requireSubcommand(1);

  auto r = std::make_shared<RenderRequest>();
  Command* render = cmd->addSubcommand(
      "render", "The panel image: one ray per subpixel along its calibrated view");
  addDisplayOption(*render, r->display, "Calibration file (visual.json)", "calibration")
      ->required();
  render->addOption("scene", r->scene.path, "Scene or mesh file (built-in scene if omitted)");
  addSceneLoadOptions(*render, r->scene.load);
  addSamplingOptions(
      *render, r->sampling,
      "Rays per subpixel (n*n over its area and its view window; 1: the formula's ray)");
  addFilterOptions(*render, r->filter, "",
                   "one view: the lens's focal spot (docs/lenticular.md, \"Prefilter\"); each "
                   "subpixel's own span of views is always integrated");
  render
      ->addOption("--distance", r->display.distance,
                  "Design viewer distance in mm, above 0 (default: the cone spans 1 m)")
      ->check(realIn(0, std::numeric_limits<double>::infinity(), Bound::Open));
  addLensReadingOptions(*render, r->display.lens, true);
  render->addOption("-o,--output", r->output, "Output folder")->captureDefault();
  render->callback([r] { runRender(*r); });

  auto s = std::make_shared<LenticularSimulateOptions>();
  Command* simulate =
      cmd->addSubcommand("simulate", "What an eye sees on the panel through the lenses");
  simulate->addOption("inputs", s->inputs,
                      "DIR of `lenticular render` [CALIBRATION], or CALIBRATION with --image");
  simulate->addOption("--image", s->image, "Panel image (instead of DIR/image.png)");
  simulate->addOption("--eye", s->eye,
                      "Eye X,Y,Z in mm (origin: panel centre, z toward the viewer; default: "
                      "the centre of the view cone at the design distance)");
  simulate
      ->addOption("--distance", s->display.distance,
                  "Design viewer distance in mm, above 0 (default eye)")
      ->check(realIn(0, std::numeric_limits<double>::infinity(), Bound::Open));
  addLensReadingOptions(*simulate, s->display.lens);
  addLimitOptions(*simulate);
  simulate->addOption("-o,--output", s->output, "Output image (.png or .pfm)")->captureDefault();
  simulate->callback([s] { runSimulate(*s); });
}

}  // namespace parallax::app
