// The command-line options of RGB-D photo input (docs/rgbd.md): --rgbd COLOUR DEPTH and how the
// depth map is read and meshed. render and view add them to their subcommands, load the scene
// through loadRgbdFromOptions instead of a scene file, and record the choices with recordRgbd.
#pragma once

#include <string>
#include <vector>

#include "parallax/io/json_writer.h"
#include "parallax/scene/rgbd.h"
#include "parallax/scene/scene.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace parallax::app {

struct RgbdCliOptions {
  std::vector<std::string> files;  // --rgbd COLOUR DEPTH; empty: not given
  std::string convention = depthConventionName(RgbdOptions{}.convention);
  std::string range = "1:3";  // --depth-range NEAR:FAR (RgbdOptions' default)
  std::string edges = rgbdEdgesName(RgbdOptions{}.edges);
  double fovDegrees = RgbdOptions{}.fovDegrees;

  bool given() const { return !files.empty(); }
  // The parsed options; throws InputError("command line", "--depth-convention" | "--depth-range"
  // | "--rgbd-edges" | "--rgbd-fov", ...) on a bad value.
  RgbdOptions options() const;
};

// Adds --rgbd, --depth-convention, --depth-range, --rgbd-edges and --rgbd-fov to `cmd`. Returns
// the --rgbd option, so that the caller can make it exclude its scene argument.
CLI::Option* addRgbdOptions(CLI::App& cmd, RgbdCliOptions& options);

// The scene of the photo (io/rgbd_file.h), its warnings printed to stderr, within the memory
// limit (--max-memory). The loader's errors name the file and the option --rgbd; bad values
// name their option (see options()).
Scene loadRgbdFromOptions(const RgbdCliOptions& options);

// The choices under /rgbd in the render record: colour, depth, convention, near, far,
// fov_degrees, edges (and edge_jump, background_offset, background_radius_px when layered),
// width_px, height_px and triangles (of `scene`, the loaded photo).
void recordRgbd(JsonWriter& record, const RgbdCliOptions& options, const Scene& scene);

}  // namespace parallax::app
