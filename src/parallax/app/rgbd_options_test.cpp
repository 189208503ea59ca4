// The RGB-D command-line glue: the options parse (cli_parser.h, CLI11 behind it), bad values are
// InputErrors naming their option, the loader's errors name --rgbd and the file, and the record
// holds the choices under /rgbd.
#include "parallax/app/cli_parser.h"
#include "parallax/app/cli_support.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <vector>

#include "parallax/app/cli_parser.h"
#include "parallax/core/error.h"
#include "parallax/io/image_file.h"
#include "parallax/io/png_encoder.h"

namespace parallax::app {
namespace {

namespace fs = std::filesystem;

// The InputError's key, or "(none)" when `f` throws none.
template <typename F>
std::string keyOfError(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.path();
  }
  return "(none)";
}

TEST(RgbdOptions, ParseThroughTheCommandLine) {
  CommandLine line;
  RgbdRequest o;
  addRgbdOptions(line.root(), o);
  const CommandLine::Outcome outcome = line.parse(
      "--rgbd photo.png depth.png --depth-convention inverse --depth-range 2:5.5 "
      "--rgbd-edges layered --rgbd-fov 65");
  ASSERT_EQ(outcome.kind, CommandLine::Outcome::Kind::Ran) << outcome.message;
  ASSERT_EQ(o.files, (std::vector<std::string>{"photo.png", "depth.png"}));
  const RgbdOptions parsed = o.options();
  EXPECT_EQ(parsed.convention, DepthConvention::Inverse);
  EXPECT_FLOAT_EQ(parsed.nearDistance, 2.0f);
  EXPECT_FLOAT_EQ(parsed.farDistance, 5.5f);
  EXPECT_EQ(parsed.edges, RgbdEdges::Layered);
  EXPECT_FLOAT_EQ(parsed.fovDegrees, 65.0f);
  // One file is not enough.
  CommandLine other;
  RgbdRequest one;
  addRgbdOptions(other.root(), one);
  const CommandLine::Outcome refused = other.parse("--rgbd photo.png");
  EXPECT_EQ(refused.kind, CommandLine::Outcome::Kind::Refused);
  EXPECT_NE(refused.message.find("--rgbd"), std::string::npos) << refused.message;
}

TEST(RgbdOptions, DefaultsAreTheLibrarys) {
  const RgbdOptions parsed = RgbdRequest{}.options();
  const RgbdOptions library;
  EXPECT_EQ(parsed.convention, library.convention);
  EXPECT_EQ(parsed.nearDistance, library.nearDistance);
  EXPECT_EQ(parsed.farDistance, library.farDistance);
  EXPECT_EQ(parsed.edges, library.edges);
  EXPECT_EQ(parsed.fovDegrees, library.fovDegrees);
}

TEST(RgbdOptions, BadValuesNameTheirOption) {
  const auto with = [](auto change) {
    RgbdRequest o;
    change(o);
    return optionName(keyOfError([&] { o.options(); }));
  };
  EXPECT_EQ(with([](RgbdRequest& o) { o.convention = "metric"; }), "--depth-convention");
  for (const char* range : {"3", "3:1", "0:2", "1:x", "nan:2", "1:2:3", "-1:2", ""})
    EXPECT_EQ(with([&](RgbdRequest& o) { o.range = range; }), "--depth-range") << range;
  EXPECT_EQ(with([](RgbdRequest& o) { o.edges = "holes"; }), "--rgbd-edges");
  EXPECT_EQ(with([](RgbdRequest& o) { o.fovDegrees = 180; }), "--rgbd-fov");
  EXPECT_EQ(with([](RgbdRequest& o) { o.fovDegrees = 0.5; }), "--rgbd-fov");
}

// The photo's scene as the request layer loads it.
Scene loadPhoto(const RgbdRequest& options) {
  jobs::SceneRequest request;
  request.rgbd = options;
  return jobs::loadSceneQuietly(request);
}

TEST(RgbdOptions, LoadsNamingRgbdAndRecordsTheChoices) {
  const fs::path dir =
      fs::temp_directory_path() / ("parallax_rgbd_options_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string colour = (dir / "c.png").string(), depth = (dir / "d.png").string();
  writeImage(colour, Image(6, 4, Vec3f(0.3f)));
  std::vector<uint16_t> codes(24);
  for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint16_t(1000 * i);
  writeFileAtomically(depth, encodePngGrey16(codes.data(), 6, 4));

  RgbdRequest o;
  o.files = {colour, (dir / "missing.png").string()};
  try {
    loadPhoto(o);
    ADD_FAILURE() << "no error for a missing depth map";
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), "{rgbd}");
    EXPECT_EQ(errorLine(e).find(e.file() + ": --rgbd: "), 0u) << errorLine(e);
    EXPECT_EQ(e.file(), (dir / "missing.png").string());
    // One line: "file: --rgbd: message", the file not repeated.
    const std::string text = e.what();
    EXPECT_EQ(text.find(e.file()), 0u) << text;
    EXPECT_EQ(text.find(e.file(), 1), std::string::npos) << text;
  }

  o.files = {colour, depth};
  o.edges = "layered";
  o.range = "2:4";
  const Scene scene = loadPhoto(o);
  EXPECT_EQ(scene.meshes.size(), 2u);
  JsonWriter record;
  recordRgbd(record, o, scene);
  const std::string json = record.dump();
  for (const char* expected :
       {"\"convention\": \"disparity\"", "\"edges\": \"layered\"", "\"near\": 2.0", "\"far\": 4.0",
        "\"fov_degrees\": 50.0", "\"width_px\": 6", "\"height_px\": 4", "\"edge_jump\"",
        "\"background_radius_px\": 2"})
    EXPECT_NE(json.find(expected), std::string::npos) << expected << " in " << json;
  EXPECT_NE(json.find("\"triangles\": " + std::to_string(scene.triangleCount())), std::string::npos)
      << json;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace parallax::app
