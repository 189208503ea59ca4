// `parallax lenticular`: slanted lenticular displays (the Looking Glass family) from their
// calibration file: render the panel's framebuffer, and see it from an eye (docs/lenticular.md).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/io/lenticular_file.h"
#include "parallax/jobs/distributed.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/render/display_render.h"
#include "parallax/sim/lenticular_sim.h"

namespace parallax::app {

namespace {

namespace fs = std::filesystem;

struct LenticularRenderOptions {
  std::string calibration, scene, output = "out";
  SceneLoadOptions load;     // --camera
  SamplingOptions sampling;  // 16 rays per subpixel over its view window, as render
  FilterOptions filter;
  double distance = 0;
};

struct LenticularSimulateOptions {
  std::vector<std::string> inputs;  // DIR [CALIBRATION], or CALIBRATION with --image
  std::string image, eye, output = "out/lenticular-view.png";
  double distance = 0;
};

void runRender(const LenticularRenderOptions& o) {
  runLenticularRender({loadDisplayOrDefault(o.calibration).lenticular, o.scene, o.output,
                       o.sampling, o.filter, o.distance, o.load, RgbdCliOptions{}});
}

void runSimulate(const LenticularSimulateOptions& o) {
  std::string imagePath = o.image, calibrationPath;
  if (!o.image.empty()) {
    if (o.inputs.size() != 1)
      throw InputError("command line", "--image", "takes the calibration file as the argument");
    calibrationPath = o.inputs[0];
  } else {
    if (o.inputs.empty() || o.inputs.size() > 2)
      throw InputError("command line", "DIR",
                       "expected DIR [CALIBRATION] or --image FILE CALIBRATION");
    imagePath = (fs::path(o.inputs[0]) / "image.png").string();
    calibrationPath =
        o.inputs.size() == 2 ? o.inputs[1] : (fs::path(o.inputs[0]) / "visual.json").string();
  }
  const LenticularDesign design =
      designLenticular(loadDisplayOrDefault(calibrationPath).lenticular, o.distance);
  const double w = design.calibration.screenW, h = design.calibration.screenH;
  checkMemoryEstimate(imageBytes(w, h, kFloatRgbPixelBytes, 2) + imageBytes(w, h, kRgba8PixelBytes),
                      calibrationPath, "the panel and the view", "use a smaller panel");
  const Image panel = readImage(imagePath);
  Vec3d eye{0, 0, design.viewDistanceMm};
  if (!o.eye.empty()) {
    const Vec3f e = parseVec3("--eye", o.eye);
    if (!(e.z > 0)) throw InputError("command line", "--eye", "the eye must be in front (z > 0)");
    eye = {e.x, e.y, e.z};
  }
  const Image view = simulateLenticularView(design, panel, eye);
  writeImage(o.output, view);
  std::printf("wrote %s (%dx%d): the panel seen from %.1f,%.1f,%.1f mm\n", o.output.c_str(),
              view.width(), view.height(), eye.x, eye.y, eye.z);
}

}  // namespace

void runLenticularRender(const LenticularRenderJob& o) {
  RenderSettings settings = o.sampling.settings();
  const ViewFilter filter = o.filter.filter();
  // The central ray is one ray: more samples of it would all be the same.
  if (filter.kind == ViewFilterKind::None) settings.samplesPerPixel = 1;
  const LenticularDesign design = designLenticular(o.calibration, o.distance);
  // Before anything is allocated: the subpixel film (three columns per pixel), the panel
  // image and its 8-bit copy; and the time of one sample per subpixel and spp.
  const double w = design.calibration.screenW, h = design.calibration.screenH;
  checkMemoryEstimate(imageBytes(3 * w, h) + imageBytes(w, h) + imageBytes(w, h, kRgba8PixelBytes),
                      o.calibration.source, "the panel image", "use a smaller panel");
  o.sampling.checkWork(3 * w, h);
  const Scene scene =
      o.rgbd.given() ? loadRgbdFromOptions(o.rgbd) : loadSceneReportingWarnings(o.scene, o.load);
  const Accelerator accelerator(scene,
                                acceleratorForCameraRays(3 * w * h * settings.samplesPerPixel));
  DisplayLayers out;
  {
    ProgressBar bar("lenticular render");
    // Under mpirun each rank renders its bands of rows; rank 0 writes (docs/distributed.md).
    out = renderDisplay(scene, accelerator, *makeLenticularDisplay(design, filter),
                        frameShare(settings),
                        [&bar](int done, int total) { bar.update(done, total); });
  }
  if (!mergeFrameShares({&out.image}, out.stats, cliReporter())) return;
  JsonWriter record;
  startRenderRecord(record, "lenticular: rays per subpixel around its view", o.calibration.source);
  record.set("/scene", scene.source);
  if (o.rgbd.given()) recordRgbd(record, o.rgbd, scene);
  if (!o.load.camera.empty()) record.set("/scene_camera", o.load.camera);  // docs/gltf.md
  record.set("/spp", settings.samplesPerPixel);
  record.set("/bounces", settings.bounces);
  record.set("/filter/kind", viewFilterName(filter.kind));
  record.set("/filter/width_views", filter.widthViews);
  record.set("/seed", o.sampling.seed);
  record.set("/seconds", out.stats.seconds);
  record.set("/rays", out.stats.totalRays());
  record.set("/outputs/image", "image.png");
  record.set("/outputs/calibration", "visual.json");
  record.set("/scene_display/center", scene.display.center);
  record.set("/scene_display/normal", scene.display.normal);
  record.set("/scene_display/up", scene.display.up);
  record.set("/scene_display/width", double(fitDisplayWidth(scene.display, displayWindow(design))));
  writeLenticularDesignJson(record, "/design", design);

  OutputSet set(o.output);
  const char* dir = set.dir().c_str();
  writeImage(set.path("image.png"), out.image);
  // The calibration beside the image, so that `lenticular simulate DIR` finds it.
  writeFileAtomically(set.path("visual.json"), lenticularCalibrationText(design.calibration));
  writeFileAtomically(set.path("render.json"), record.dump() + "\n");
  set.commit();
  std::printf("wrote %s/image.png (%dx%d), %s/visual.json, %s/render.json\n", dir,
              out.image.width(), out.image.height(), dir, dir);
  std::printf("%.2f pixels per lens, views over %.0f degrees; %d spp in %.2f s, %s\n",
              design.pixelsPerLens, design.calibration.viewConeDegrees, settings.samplesPerPixel,
              out.stats.seconds,
              formatRate(double(out.stats.totalRays()) / out.stats.seconds).c_str());
}

void registerLenticularCommand(CLI::App& cli) {
  CLI::App* cmd = cli.add_subcommand(
      "lenticular", "Slanted lenticular displays (Looking Glass family) from their visual.json");
  cmd->require_subcommand(1);

  auto r = std::make_shared<LenticularRenderOptions>();
  CLI::App* render = cmd->add_subcommand(
      "render", "The panel image: one ray per subpixel along its calibrated view");
  render->add_option("calibration", r->calibration, "Calibration file (visual.json)")->required();
  render->add_option("scene", r->scene, "Scene or mesh file (built-in scene if omitted)");
  addSceneLoadOptions(*render, r->load);
  addSamplingOptions(
      *render, r->sampling,
      "Rays per subpixel (n*n over its area and its view window; 1: the formula's ray)");
  addFilterOptions(*render, r->filter, "",
                   "one view: a pixel's step of view fraction, pitch_px / screenW, the spacing "
                   "of one colour channel's views");
  render
      ->add_option("--distance", r->distance,
                   "Design viewer distance in mm, above 0 (default: the cone spans 1 m)")
      ->check(realIn(0, std::numeric_limits<double>::infinity(), Bound::Open));
  render->add_option("-o,--output", r->output, "Output folder")->capture_default_str();
  render->callback([r] { runRender(*r); });

  auto s = std::make_shared<LenticularSimulateOptions>();
  CLI::App* simulate =
      cmd->add_subcommand("simulate", "What an eye sees on the panel through the lenses");
  simulate->add_option("inputs", s->inputs,
                       "DIR of `lenticular render` [CALIBRATION], or CALIBRATION with --image");
  simulate->add_option("--image", s->image, "Panel image (instead of DIR/image.png)");
  simulate->add_option("--eye", s->eye,
                       "Eye X,Y,Z in mm (origin: panel centre, z toward the viewer; default: "
                       "the centre of the view cone at the design distance)");
  simulate
      ->add_option("--distance", s->distance, "Design viewer distance in mm, above 0 (default eye)")
      ->check(realIn(0, std::numeric_limits<double>::infinity(), Bound::Open));
  addLimitOptions(*simulate);
  simulate->add_option("-o,--output", s->output, "Output image (.png or .pfm)")
      ->capture_default_str();
  simulate->callback([s] { runSimulate(*s); });
}

}  // namespace parallax::app
