// `parallax view`: an ordinary pinhole-camera picture of a scene.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/camera/display_camera.h"
#include "parallax/camera/framing.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/image_file.h"
#include "parallax/jobs/distributed.h"
#include "parallax/jobs/sequence.h"
#include "parallax/render/render.h"

namespace parallax::app {

namespace {

struct ViewOptions {
  std::string scene;
  SceneLoadOptions load;  // --camera
  std::string eye, lookAt, up, size;
  std::string displayEye, display;
  FramingOptions framing;  // with --display-eye: framed as render frames it
  std::optional<float> fov;
  SamplingOptions sampling;
  std::string output = "out/view.png";
  SequenceOptions sequence;  // numbered pictures, OUTPUT-NNNN.png (docs/animation.md)
  RgbdCliOptions rgbd;       // --rgbd COLOUR DEPTH instead of a scene (docs/rgbd.md)
};

// The camera of `view`: an ordinary pinhole camera, or with --display-eye the ideal window
// view of the display from that eye.
std::unique_ptr<Camera> makeCamera(const ViewOptions& o, const Scene& scene) {
  int width = 960, height = 540;
  if (!o.displayEye.empty()) {
    const DisplayDescription description = loadDisplayOrDefault(o.display);
    if (description.kind == DisplayKind::Lenticular) {
      // A lenticular render places the scene as it is: so does its ideal view.
      if (o.framing.given())
        throw InputError("command line", "--fit/--focus/--depth-budget",
                         "apply to barrier displays (their depth budget is the virtual gap)");
      const std::unique_ptr<DisplayModel> display =
          makeLenticularDisplay(designLenticular(description.lenticular));
      width = display->film().panelWidth, height = display->film().panelHeight;
      if (!o.size.empty()) parseSize("--size", o.size, width, height);
      const Vec3f eye = parseVec3("--display-eye", o.displayEye);
      if (!(eye.z > 0))
        throw InputError("command line", "--display-eye", "the eye must be in front (z > 0 mm)");
      return std::make_unique<WindowCamera>(Vec3d{eye.x, eye.y, eye.z}, *display, scene.display,
                                            width, height);
    }
    const DisplayDesign design = designDisplay(description.barrier);
    const Panel& front = design.spec.order == LayerOrder::BarrierBack ? design.spec.imagePanel
                                                                      : design.spec.maskPanel;
    width = front.width, height = front.height;
    if (!o.size.empty()) parseSize("--size", o.size, width, height);
    const Vec3f eye = parseVec3("--display-eye", o.displayEye);
    if (!(eye.z > 0))
      throw InputError("command line", "--display-eye", "the eye must be in front (z > 0 mm)");
    // Framed as `render` frames it (camera/framing.h), so that this is what the render shows.
    Scene placed;
    placed.display = scene.display;
    if (!placed.display.content) placed.display.content = scene.bounds();
    o.framing.apply(placed.display);
    const Framing framing = frameForDisplay(placed, design);
    return std::make_unique<WindowCamera>(Vec3d{eye.x, eye.y, eye.z}, framing.design,
                                          framing.placement, width, height);
  }
  if (!o.size.empty()) parseSize("--size", o.size, width, height);
  CameraSpec spec = scene.camera ? *scene.camera : frameScene(scene);
  if (!o.eye.empty()) spec.eye = parseVec3("--eye", o.eye);
  if (!o.lookAt.empty()) spec.lookAt = parseVec3("--look-at", o.lookAt);
  if (!o.up.empty()) spec.up = parseVec3("--up", o.up);
  if (o.fov) spec.fovDegrees = *o.fov;  // (0, 180), checked by the option
  if (length(cross(spec.lookAt - spec.eye, spec.up)) == 0.0f)
    throw InputError("command line", "--up", "must not be parallel to the view direction");
  return std::make_unique<PinholeCamera>(spec.eye, spec.lookAt, spec.up, spec.fovDegrees, width,
                                         height);
}

void runView(const ViewOptions& o) {
  const RenderSettings settings = o.sampling.settings();
  o.sequence.videoOptions();  // refuses bad --video options before any work
  Scene scene =
      o.rgbd.given() ? loadRgbdFromOptions(o.rgbd) : loadSceneReportingWarnings(o.scene, o.load);
  noteAnimation(o.sequence, scene, cliReporter());
  const std::unique_ptr<Camera> camera = makeCamera(o, scene);
  // Before anything is allocated: the film and the writer's 8-bit copy, and the time.
  const std::string size = std::to_string(camera->width()) + "x" + std::to_string(camera->height());
  checkMemoryEstimate(imageBytes(camera->width(), camera->height()) +
                          imageBytes(camera->width(), camera->height(), kRgba8PixelBytes),
                      (o.size.empty() ? "image " : "--size ") + size, "the film",
                      "use a smaller size");
  checkPixelCount(double(camera->width()) * camera->height(), "--size " + size);
  o.sampling.checkWork(camera->width(), camera->height());
  const AcceleratorOptions acceleratorOptions =
      acceleratorForCameraRays(double(camera->width()) * camera->height() * o.sampling.spp);
  // One picture under mpirun: each rank renders its bands, rank 0 writes (docs/distributed.md);
  // a sequence's pictures are whole frames of one rank.
  const auto renderPicture = [&](const Scene& posed, const Accelerator& accelerator,
                                 const Camera& frameCamera, const std::string& output, bool split) {
    RenderStats stats;
    Image image;
    {
      ProgressBar bar("view");
      image = render(posed, accelerator, frameCamera, split ? frameShare(settings) : settings,
                     &stats, [&bar](int done, int total) { bar.update(done, total); });
    }
    if (split && !mergeFrameShares({&image}, stats, cliReporter())) return;
    writeImage(output, image);
    std::printf("wrote %s (%dx%d, %d spp) in %.2f s, %s\n", output.c_str(), frameCamera.width(),
                frameCamera.height(), o.sampling.spp, stats.seconds,
                formatRate(double(stats.totalRays()) / stats.seconds).c_str());
  };
  if (!o.sequence.given()) {
    const Accelerator accelerator(scene, acceleratorOptions);
    renderPicture(scene, accelerator, *camera, o.output, true);
    return;
  }
  const SequencePlan plan = planSequence(o.sequence, scene);
  prepareFraming(scene, plan);
  FrameJob job;
  job.reporter = &cliReporter();
  job.accelerator = acceleratorOptions;
  job.finished = [&](int frame) {
    return std::filesystem::is_regular_file(numberedPicture(o.output, frame));
  };
  job.render = [&](const Scene& posed, const Accelerator& accelerator, int frame) {
    renderPicture(posed, accelerator, *makeCamera(o, posed), numberedPicture(o.output, frame),
                  false);
  };
  runSequence(plan, scene, job);
  writeSequenceVideo(
      o.sequence, plan, [&](int frame) { return numberedPicture(o.output, frame); }, cliReporter());
}

}  // namespace

void registerViewCommand(CLI::App& cli) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* cmd = cli.add_subcommand("view", "Render an ordinary pinhole-camera picture");
  CLI::Option* sceneOption = cmd->add_option(
      "scene", options->scene,
      "Scene file (.json) or mesh (.obj .ply .stl .gltf .glb); built-in scene if omitted");
  addRgbdOptions(*cmd, options->rgbd)->excludes(sceneOption);
  addSceneLoadOptions(*cmd, options->load);
  cmd->add_option("--eye", options->eye, "Camera position X,Y,Z (scene units)");
  cmd->add_option("--look-at", options->lookAt, "Point the camera looks at, X,Y,Z");
  cmd->add_option("--up", options->up, "Up direction X,Y,Z");
  cmd->add_option("--fov", options->fov, "Vertical field of view in degrees, above 0 and below 180")
      ->check(realIn(0, 180, Bound::Open, Bound::Open));
  cmd->add_option("--size", options->size,
                  "Image size WIDTHxHEIGHT (960x540; the front layer's with --display-eye)");
  cmd->add_option("--display-eye", options->displayEye,
                  "Ideal view through the display window from this eye X,Y,Z (display mm, "
                  "origin at the front layer's centre, z toward the viewer)");
  cmd->add_option("--display", options->display,
                  "Display for --display-eye: a file of any kind, or lkg:NAME");
  addFramingOptions(*cmd, options->framing, "With --display-eye: ");
  addSamplingOptions(*cmd, options->sampling, "Samples per pixel (n*n is stratified)");
  cmd->add_option("-o,--output", options->output, "Output image (.png, or .pfm linear float)")
      ->capture_default_str();
  addSequenceOptions(*cmd, options->sequence, "the numbered pictures");
  cmd->callback([options] { runView(*options); });
}

}  // namespace parallax::app
