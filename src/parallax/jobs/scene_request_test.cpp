// The scene a request names (jobs/scene_request.h): the built-in scene and a file loaded as the
// loaders load them, the RGB-D options and the look refused by field, and the record.
#include "parallax/jobs/scene_request.h"

#include <gtest/gtest.h>

#include <string>

#include "parallax/importer/scene_file.h"
#include "parallax/jobs/jobs_test_support.h"

namespace parallax::jobs {
namespace {

TEST(SceneRequest, LoadsWhatTheLoadersLoad) {
  const SceneRequest builtIn;
  EXPECT_EQ(loadSceneQuietly(builtIn).triangleCount(), defaultScene().triangleCount());
  SceneRequest file;
  file.path = PARALLAX_SOURCE_DIR "/scenes/textured.json";
  EXPECT_EQ(loadSceneQuietly(file).triangleCount(), parallax::loadScene(file.path).triangleCount());
  // The look over the scene's own.
  file.load.exposureStops = 1.5;
  file.load.viewTransform = "filmic";
  const Scene looked = loadSceneQuietly(file);
  EXPECT_EQ(looked.look.exposureStops, 1.5);
  EXPECT_EQ(looked.look.transform, *parseViewTransform("filmic"));
  JsonWriter record;
  recordScene(record, file, looked);
  const std::string json = record.dump();
  EXPECT_NE(json.find("\"view_transform\": \"filmic\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"exposure\": 1.5"), std::string::npos) << json;
}

TEST(SceneRequest, RefusalsNameTheirField) {
  SceneRequest r;
  r.load.camera = "front";
  EXPECT_EQ(fieldOf([&] { loadSceneQuietly(r); }), "camera");  // the built-in has none
  r.load.camera.clear(), r.load.exposureStops = 40;
  EXPECT_EQ(fieldOf([&] { loadSceneQuietly(r); }), "exposure");
  r.load.exposureStops.reset(), r.load.viewTransform = "sepia";
  EXPECT_EQ(fieldOf([&] { loadSceneQuietly(r); }), "view_transform");
  RgbdRequest rgbd;
  rgbd.files = {"colour.png"};
  r = SceneRequest{};
  r.rgbd = rgbd;
  EXPECT_EQ(fieldOf([&] { loadSceneQuietly(r); }), "rgbd");  // two files: COLOUR DEPTH
  for (const auto& [field, set] : std::vector<std::pair<std::string, void (*)(RgbdRequest&)>>{
           {"depth_convention", [](RgbdRequest& q) { q.convention = "height"; }},
           {"depth_range", [](RgbdRequest& q) { q.range = "2:1"; }},
           {"rgbd_edges", [](RgbdRequest& q) { q.edges = "soft"; }},
           {"rgbd_fov", [](RgbdRequest& q) { q.fovDegrees = 180; }}}) {
    RgbdRequest q;
    set(q);
    EXPECT_EQ(fieldOf([&] { q.options(); }), field);
  }
  EXPECT_NO_THROW(RgbdRequest{}.options());
}

}  // namespace
}  // namespace parallax::jobs
