// `parallax view`: an ordinary pinhole-camera picture of a scene.
#include <memory>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/jobs/distributed.h"
#include "parallax/jobs/sequence.h"
#include "parallax/jobs/view_job.h"

namespace parallax::app {

namespace {

// The request, and the options the command line spells as text (X,Y,Z and WxH).
struct ViewOptions {
  ViewRequest request;
  std::string eye, lookAt, up, size, displayEye;
};

void runView(ViewOptions o) {
  ViewRequest& r = o.request;
  r.scene.load.import = importOptions();
  if (!o.size.empty()) parseSize("--size", o.size, r.width, r.height);
  if (!o.displayEye.empty()) {
    const Vec3f eye = parseVec3("--display-eye", o.displayEye);
    r.displayEye = Vec3d{eye.x, eye.y, eye.z};
  }
  // Given with --display-eye too, so that the request refuses the mix (jobs::viewCamera).
  if (!o.eye.empty()) r.eye = parseVec3("--eye", o.eye);
  if (!o.lookAt.empty()) r.lookAt = parseVec3("--look-at", o.lookAt);
  if (!o.up.empty()) r.up = parseVec3("--up", o.up);
  jobs::runView(r, cliReporter());
}

}  // namespace

void registerViewCommand(Command& cli) {
  auto options = std::make_shared<ViewOptions>();
  ViewRequest& request = options->request;
  Command* cmd = cli.addSubcommand("view", "Render an ordinary pinhole-camera picture");
  Option* sceneOption = cmd->addOption(
      "scene", request.scene.path,
      "Scene file (.json) or mesh (.obj .ply .stl .gltf .glb, and through assimp .fbx .dae .3ds "
      ".blend and the rest of docs/import.md); built-in scene if omitted");
  addRgbdOptions(*cmd, request.scene.rgbd)->excludes(sceneOption);
  addSceneLoadOptions(*cmd, request.scene.load);
  cmd->addOption("--eye", options->eye, "Camera position X,Y,Z (scene units)");
  cmd->addOption("--look-at", options->lookAt, "Point the camera looks at, X,Y,Z");
  cmd->addOption("--up", options->up, "Up direction X,Y,Z");
  cmd->addOption("--fov", request.fov, "Vertical field of view in degrees, above 0 and below 180")
      ->check(realIn(0, 180, Bound::Open, Bound::Open));
  cmd->addOption("--size", options->size,
                 "Image size WIDTHxHEIGHT (960x540; the front layer's with --display-eye)");
  cmd->addOption("--display-eye", options->displayEye,
                 "Ideal view through the display window from this eye X,Y,Z (display mm, "
                 "origin at the front layer's centre, z toward the viewer)");
  addDisplayOption(*cmd, request.display,
                   "Display for --display-eye: a file of any kind, or lkg:NAME");
  addFramingOptions(*cmd, request.framing, "With --display-eye: ");
  addSamplingOptions(*cmd, request.sampling, "Samples per pixel (n*n is stratified)");
  cmd->addOption("-o,--output", request.output, "Output image (.png, or .pfm linear float)")
      ->captureDefault();
  addSequenceOptions(*cmd, request.sequence, "the numbered pictures");
  cmd->callback([options] { runView(*options); });
}

}  // namespace parallax::app
