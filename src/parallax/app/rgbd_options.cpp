#include "parallax/app/rgbd_options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "parallax/app/cli_support.h"
#include "parallax/core/error.h"
#include "parallax/io/rgbd_file.h"

namespace parallax::app {

namespace {

// A finite number filling all of `text`, or false.
bool parseNumber(const std::string& text, double& value) {
  const char* end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && stop == end && std::isfinite(value);
}

}  // namespace

RgbdOptions RgbdCliOptions::options() const {
  RgbdOptions o;
  if (convention == "disparity")
    o.convention = DepthConvention::Disparity;
  else if (convention == "depth")
    o.convention = DepthConvention::Depth;
  else if (convention == "inverse")
    o.convention = DepthConvention::Inverse;
  else
    throw InputError("command line", "--depth-convention",
                     "expected disparity, depth or inverse, got '" + convention + "'");

  const size_t colon = range.find(':');
  double nearZ = 0, farZ = 0;
  if (colon == std::string::npos || !parseNumber(range.substr(0, colon), nearZ) ||
      !parseNumber(range.substr(colon + 1), farZ))
    throw InputError("command line", "--depth-range",
                     "expected NEAR:FAR (two numbers, scene units), got '" + range + "'");
  if (!(nearZ > 0 && farZ > nearZ && farZ <= 1e6 * nearZ))
    throw InputError("command line", "--depth-range",
                     "needs 0 < NEAR < FAR <= 1e6 NEAR, got '" + range + "'");
  o.nearDistance = float(nearZ);
  o.farDistance = float(farZ);

  if (edges == "stretch")
    o.edges = RgbdEdges::Stretch;
  else if (edges == "layered")
    o.edges = RgbdEdges::Layered;
  else
    throw InputError("command line", "--rgbd-edges",
                     "expected stretch or layered, got '" + edges + "'");

  if (!(fovDegrees >= 1.0 && fovDegrees <= 170.0))
    throw InputError("command line", "--rgbd-fov",
                     "must be a number of degrees in [1, 170], got " + std::to_string(fovDegrees));
  o.fovDegrees = float(fovDegrees);
  return o;
}

CLI::Option* addRgbdOptions(CLI::App& cmd, RgbdCliOptions& options) {
  CLI::Option* rgbd =
      cmd.add_option("--rgbd", options.files,
                     "An RGB-D photo instead of a scene: a colour image and its greyscale depth "
                     "map (8- or 16-bit PNG) of the same size (docs/rgbd.md)")
          ->expected(2)
          ->type_name("COLOUR DEPTH");
  cmd.add_option("--depth-convention", options.convention,
                 "With --rgbd: how the depth map's values give distance: disparity (bright = "
                 "near, linear in 1/distance: MiDaS, Depth-Anything), depth (bright = far, "
                 "linear), inverse (bright = near, linear)")
      ->type_name("disparity|depth|inverse")
      ->capture_default_str();
  cmd.add_option("--depth-range", options.range,
                 "With --rgbd: the distances of the nearest and farthest values, in scene units; "
                 "only their ratio shapes the picture (the framing scales it to the display)")
      ->type_name("NEAR:FAR")
      ->capture_default_str();
  cmd.add_option("--rgbd-edges", options.edges,
                 "With --rgbd: at depth jumps, stretch (one sheet, rubber sheets across the "
                 "jumps) or layered (cut at jumps, a background sheet extended from the far side "
                 "fills them)")
      ->type_name("stretch|layered")
      ->capture_default_str();
  cmd.add_option("--rgbd-fov", options.fovDegrees,
                 "With --rgbd: the photo's horizontal field of view in degrees")
      ->check(realIn(1.0, 170.0))
      ->type_name("DEGREES")
      ->capture_default_str();
  return rgbd;
}

Scene loadRgbdFromOptions(const RgbdCliOptions& options) {
  if (options.files.size() != 2)
    throw InputError("command line", "--rgbd", "expected two files: COLOUR DEPTH");
  const RgbdOptions rgbd = options.options();
  Scene scene;
  try {
    scene = loadRgbdScene(options.files[0], options.files[1], rgbd, memoryLimitBytes());
  } catch (const InputError& e) {
    // The loader names the file; the key that gave it is --rgbd. InputError's text is
    // "file: message" when it has no key.
    if (!e.path().empty()) throw;
    std::string message = e.what();
    const std::string prefix = e.file() + ": ";
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    throw InputError(e.file(), "--rgbd", message);
  }
  for (const auto& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  return scene;
}

void recordRgbd(JsonWriter& record, const RgbdCliOptions& options, const Scene& scene) {
  const RgbdOptions o = options.options();
  if (options.files.size() == 2) {
    record.set("/rgbd/colour", options.files[0]);
    record.set("/rgbd/depth", options.files[1]);
  }
  record.set("/rgbd/convention", depthConventionName(o.convention));
  record.set("/rgbd/near", double(o.nearDistance));
  record.set("/rgbd/far", double(o.farDistance));
  record.set("/rgbd/fov_degrees", double(o.fovDegrees));
  record.set("/rgbd/edges", rgbdEdgesName(o.edges));
  if (o.edges == RgbdEdges::Layered) {
    record.set("/rgbd/edge_jump", double(o.edgeJump));
    record.set("/rgbd/background_offset", double(o.backgroundOffset));
  }
  if (!scene.images.empty()) {
    const Image& photo = scene.images[0];
    record.set("/rgbd/width_px", photo.width());
    record.set("/rgbd/height_px", photo.height());
    if (o.edges == RgbdEdges::Layered)
      record.set("/rgbd/background_radius_px", backgroundRadiusPx(o, photo.width()));
  }
  record.set("/rgbd/triangles", uint64_t(scene.triangleCount()));
}

}  // namespace parallax::app
