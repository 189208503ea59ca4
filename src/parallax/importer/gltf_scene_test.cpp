// glTF cameras, KHR_lights_punctual lights and COLOR_0 vertex colours from a file written by
// the test (every value known by construction), 2CylinderEngine's camera read by hand from
// its JSON chunk, and --camera's choice and display placement (importer/scene_file.h).
#include "parallax/importer/mesh_test_support.h"
#include "parallax/importer/scene_file.h"

namespace parallax {
namespace {

using namespace meshtest;

// Two triangles, in meshes 0 and 1 with float VEC3 and normalised-ubyte VEC4 colours, two
// cameras and three lights:
//   node 0: mesh 0 at (2, 1, 0)          node 1: mesh 1 at (2, 1, -1)
//   node 2: camera 0 'Front' at (0, 0, 5), looking down -z
//   node 3: light 0 (point) at (1, 2, 3)
//   node 4: light 1 (spot) at (0, 4, 0), turned -90 degrees about x: it points down -y
//   node 5: light 2 (directional), unturned: it shines along -z
//   node 6: camera 1 'Side' at (5, 0, 0), turned 90 degrees about y: it looks down -x
//   node 7: camera 2, orthographic (ignored)
std::string lightsAndColoursGltf() {
  Bytes buffer;
  const Vec3f positions[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (const Vec3f& p : positions) buffer.f32(p.x).f32(p.y).f32(p.z);  // 36 bytes
  const Vec3f colors[3] = {{0.25f, 0.5f, 1.0f}, {1, 0, 0}, {0, 0, 0.125f}};
  for (const Vec3f& c : colors) buffer.f32(c.x).f32(c.y).f32(c.z);  // 36 bytes
  const uint8_t bytes[3][4] = {{255, 128, 0, 255}, {0, 51, 255, 10}, {0, 0, 0, 0}};
  for (const auto& c : bytes)
    for (uint8_t b : c) buffer.put(b);  // 12 bytes
  const double s = std::sqrt(0.5);
  std::ostringstream json;
  json << R"({"asset": {"version": "2.0"}, "scene": 0,
  "extensionsUsed": ["KHR_lights_punctual"], "extensionsRequired": ["KHR_lights_punctual"],
  "scenes": [{"nodes": [0, 1, 2, 3, 4, 5, 6, 7]}],
  "nodes": [
    {"mesh": 0, "translation": [2, 1, 0]},
    {"mesh": 1, "translation": [2, 1, -1]},
    {"camera": 0, "translation": [0, 0, 5]},
    {"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"translation": [0, 4, 0], "rotation": [)"
       << -s << ", 0, 0, " << s << R"(],
     "extensions": {"KHR_lights_punctual": {"light": 1}}},
    {"extensions": {"KHR_lights_punctual": {"light": 2}}},
    {"camera": 1, "name": "side node", "translation": [5, 0, 0], "rotation": [0, )"
       << s << ", 0, " << s << R"(]},
    {"camera": 2}],
  "cameras": [
    {"name": "Front", "type": "perspective",
     "perspective": {"yfov": 0.5, "aspectRatio": 1.5, "znear": 0.1, "zfar": 100}},
    {"name": "Side", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}},
    {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0, "zfar": 9}}],
  "extensions": {"KHR_lights_punctual": {"lights": [
    {"type": "point", "color": [1, 0.5, 0.25], "intensity": 683},
    {"type": "spot", "intensity": 1366, "range": 10,
     "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
    {"type": "directional", "color": [0, 1, 0], "intensity": 6.83}]}},
  "materials": [{"name": "a", "pbrMetallicRoughness": {"metallicFactor": 0.5}}, {"name": "b"}],
  "meshes": [
    {"primitives": [{"attributes": {"POSITION": 0, "COLOR_0": 1}, "material": 0}]},
    {"primitives": [{"attributes": {"POSITION": 0, "COLOR_0": 2}, "material": 1}]}],
  "buffers": [{"byteLength": )"
       << buffer.data.size() << R"(, "uri": "data:application/octet-stream;base64,)"
       << base64(buffer.data) << R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 72, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5121, "normalized": true, "count": 3, "type": "VEC4"}]})";
  return json.str();
}

// The colour of the mesh vertex at `position`.
Vec3f colorAt(const TriangleMesh& mesh, const Vec3f& position) {
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    if (length(mesh.positions[i] - position) < 1e-6f) return mesh.colors.at(i);
  ADD_FAILURE() << "no vertex at " << position.x << "," << position.y << "," << position.z;
  return Vec3f(-1.0f);
}

TEST(Gltf, VertexColoursFromFloatAndNormalisedBytes) {
  TempDir dir;
  const std::string path = dir.file("lit.gltf");
  writeFile(path, lightsAndColoursGltf());
  const Scene scene = load(path);
  ASSERT_EQ(scene.meshes.size(), 2u);
  for (const TriangleMesh& mesh : scene.meshes) ASSERT_EQ(mesh.colors.size(), 3u);
  const TriangleMesh& floats =
      scene.meshes[0].positions[0].z == 0 ? scene.meshes[0] : scene.meshes[1];
  const TriangleMesh& bytes = &floats == &scene.meshes[0] ? scene.meshes[1] : scene.meshes[0];
  // Float colours as they are (linear); bytes / 255, the alpha dropped.
  expectNear(colorAt(floats, {2, 1, 0}), {0.25f, 0.5f, 1.0f});
  expectNear(colorAt(floats, {3, 1, 0}), {1, 0, 0});
  expectNear(colorAt(floats, {2, 2, 0}), {0, 0, 0.125f});
  expectNear(colorAt(bytes, {2, 1, -1}), {1, 128 / 255.0f, 0});
  expectNear(colorAt(bytes, {3, 1, -1}), {0, 51 / 255.0f, 1});
}

TEST(Gltf, PunctualLightsInOurUnits) {
  TempDir dir;
  const std::string path = dir.file("lit.gltf");
  writeFile(path, lightsAndColoursGltf());
  const Scene scene = load(path);
  ASSERT_EQ(scene.lights.size(), 3u);
  // Candela and lux / 683 lm/W: W/sr and W/m^2.
  const Light& point = scene.lights[0];
  EXPECT_EQ(point.kind, Light::Kind::Point);
  expectNear(point.position, {1, 2, 3});
  expectNear(point.intensity, {1, 0.5f, 0.25f});
  const Light& spot = scene.lights[1];
  ASSERT_EQ(spot.kind, Light::Kind::Spot);
  expectNear(spot.position, {0, 4, 0});
  expectNear(spot.direction, {0, -1, 0});
  expectNear(spot.intensity, Vec3f(2.0f));
  EXPECT_FLOAT_EQ(spot.innerCone, 0.2f);
  EXPECT_FLOAT_EQ(spot.outerCone, 0.5f);
  const Light& sun = scene.lights[2];
  ASSERT_EQ(sun.kind, Light::Kind::Directional);
  expectNear(sun.direction, {0, 0, -1});
  expectNear(sun.intensity, {0, 0.01f, 0});
  // The note lists what was taken and, of what the file has, what was ignored.
  ASSERT_EQ(scene.notes.size(), 1u);
  const std::string& note = scene.notes[0];
  for (const char* part : {"2 meshes", "2 cameras", "3 lights", "vertex colours",
                           "metallic/roughness", "1 orthographic camera", "range of 1 light"})
    EXPECT_NE(note.find(part), std::string::npos) << "'" << note << "' lacks '" << part << "'";
  for (const char* absent : {"normal maps", "skin", "animation", "samplers"})
    EXPECT_EQ(note.find(absent), std::string::npos) << "'" << note << "' has '" << absent << "'";
}

TEST(Gltf, PerspectiveCamerasWithTheirNodeTransforms) {
  TempDir dir;
  const std::string path = dir.file("lit.gltf");
  writeFile(path, lightsAndColoursGltf());
  const Scene scene = load(path);
  ASSERT_EQ(scene.cameras.size(), 2u);  // the orthographic one is left out
  const NamedCamera& front = scene.cameras[0];
  EXPECT_EQ(front.name, "Front");
  expectNear(front.spec.eye, {0, 0, 5});
  expectNear(normalize(front.spec.lookAt - front.spec.eye), {0, 0, -1});
  expectNear(front.spec.up, {0, 1, 0});
  EXPECT_NEAR(front.spec.fovDegrees, 0.5 * 180 / M_PI, 1e-4);
  EXPECT_FLOAT_EQ(front.aspectRatio, 1.5f);
  EXPECT_FLOAT_EQ(front.znear, 0.1f);
  const NamedCamera& side = scene.cameras[1];
  EXPECT_EQ(side.name, "Side");
  expectNear(side.spec.eye, {5, 0, 0});
  expectNear(normalize(side.spec.lookAt - side.spec.eye), {-1, 0, 0});
  EXPECT_FLOAT_EQ(side.aspectRatio, 0.0f);
}

// The bare file as a scene: its own lights (no default key), its first camera, and the
// display on that camera's line of sight, facing it.
TEST(Gltf, FirstCameraFramesTheSceneAndPlacesTheDisplay) {
  TempDir dir;
  const std::string path = dir.file("lit.gltf");
  writeFile(path, lightsAndColoursGltf());
  const Scene scene = loadScene(path);
  EXPECT_EQ(scene.lights.size(), 3u);
  EXPECT_EQ(scene.ambient, Vec3f(0.0f));
  ASSERT_TRUE(scene.camera);
  expectNear(scene.camera->eye, {0, 0, 5});
  // Content (2..3, 1..2, -1..0): its centre is 5.5 in front of the camera, off its axis; the
  // display's centre is on the axis at that depth.
  expectNear(scene.display.center, {0, 0, -0.5f});
  expectNear(scene.display.normal, {0, 0, 1});
  expectNear(scene.display.up, {0, 1, 0});
  ASSERT_TRUE(scene.display.fit);
  EXPECT_EQ(scene.display.fit->lo, Vec3f(2, 1, -1));
  // The shot the camera fit frames: its line of sight meets nothing, so the focus distance is
  // the content centre's depth.
  ASSERT_TRUE(scene.display.shot);
  EXPECT_FLOAT_EQ(scene.display.shot->focusDistance, 5.5f);
  EXPECT_FLOAT_EQ(scene.display.shot->yfovRadians, 0.5f);
  EXPECT_FLOAT_EQ(scene.display.shot->aspectRatio, 1.5f);
  EXPECT_EQ(scene.display.shot->focusSource, "the content's centre");
  ASSERT_FALSE(scene.notes.empty());
  EXPECT_NE(scene.notes[0].find("camera 0 'Front' used"), std::string::npos) << scene.notes[0];
  // The spot points down from (0, 4, 0) with a 0.5 rad cone; the nearest corner, (2, 1, 0), is
  // atan(2 / 3) = 0.59 rad off its axis: it lights nothing.
  const auto spotWarnings =
      std::count_if(scene.warnings.begin(), scene.warnings.end(), [](const std::string& w) {
        return w.find("light 1 (a spot) points away") != std::string::npos;
      });
  EXPECT_EQ(spotWarnings, 1) << "warnings: " << scene.warnings.size();
}

TEST(Gltf, CameraOptionChoosesByNameOrIndex) {
  TempDir dir;
  const std::string path = dir.file("lit.gltf");
  writeFile(path, lightsAndColoursGltf());
  for (const char* choice : {"Side", "side node", "1"}) {
    SceneLoadOptions options;
    options.camera = choice;
    const Scene scene = loadScene(path, options);
    ASSERT_TRUE(scene.camera);
    expectNear(scene.camera->eye, {5, 0, 0});
    // Looking down -x: the display faces +x, and its centre is on the line y = z = 0 at the
    // content centre's depth, x = 2.5.
    expectNear(scene.display.normal, {1, 0, 0});
    expectNear(scene.display.center, {2.5f, 0, 0});
    EXPECT_NEAR(scene.camera->fovDegrees, 0.8 * 180 / M_PI, 1e-4);
  }
  SceneLoadOptions unknown;
  unknown.camera = "Top";
  try {
    loadScene(path, unknown);
    ADD_FAILURE() << "no RequestError";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "camera");
    const std::string what = e.message();
    for (const char* part : {"no camera 'Top'", "0 'Front'", "1 'Side'"})
      EXPECT_NE(what.find(part), std::string::npos) << "'" << what << "' lacks '" << part << "'";
  }
  unknown.camera = "2";  // the orthographic camera has no index
  EXPECT_THROW(loadScene(path, unknown), InputError);
}

// A .json scene with the file as a mesh object, moved by its transform: no camera unless
// --camera picks one (in world space), and the scene's display width stays.
TEST(Gltf, JsonSceneCamerasAreChosenOnlyOnRequest) {
  TempDir dir;
  writeFile(dir.file("lit.gltf"), lightsAndColoursGltf());
  const std::string scenePath = dir.file("scene.json");
  writeFile(scenePath, R"({"objects": [{"shape": "mesh", "file": "lit.gltf",
    "transform": [{"translate": [0, 10, 0]}]}], "display": {"width": 3}})");
  const Scene plain = loadScene(scenePath);
  EXPECT_EQ(plain.cameras.size(), 2u);
  expectNear(plain.display.normal, {0, 0, 1});  // the scene's own
  SceneLoadOptions options;
  options.camera = "Side";
  const Scene chosen = loadScene(scenePath, options);
  ASSERT_TRUE(chosen.camera);
  expectNear(chosen.camera->eye, {5, 10, 0});
  expectNear(chosen.display.normal, {1, 0, 0});
  expectNear(chosen.display.center, {2.5f, 10, 0});
  EXPECT_FLOAT_EQ(chosen.display.width, 3.0f);
  EXPECT_FALSE(chosen.display.fit);
}

// simulate --reference loads the scene as the render did: with the camera render.json records.
TEST(Gltf, SceneAsRenderedUsesTheRecordedCamera) {
  TempDir dir;
  const std::string path = dir.file("lit.gltf");
  writeFile(path, lightsAndColoursGltf());
  writeFile(dir.file("render.json"), R"({"scene_camera": "Side"})");
  const Scene scene = loadSceneAsRendered(path, dir.file(""));
  ASSERT_TRUE(scene.camera);
  expectNear(scene.camera->eye, {5, 0, 0});
  expectNear(scene.display.normal, {1, 0, 0});
  writeFile(dir.file("render.json"), "{}");
  expectNear(loadSceneAsRendered(path, dir.file("")).camera->eye, {0, 0, 5});
}

// 2CylinderEngine.glb's only camera, node 81 (read by hand from the file's JSON chunk): a
// column-major matrix with columns x = (0.70711, -2.2e-7, -0.70711), y = (-0.33129, 0.88345,
// -0.33129), z = (0.62470, 0.46852, 0.62470), translation (1005.987, 766.317, 953.346), and
// perspective yfov 0.3143463730812073, aspectRatio 1, znear 0.05.
TEST_F(RealModels, CylinderEngineCamera) {
  const std::string path = model("assimp/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  const Scene scene = load(path);
  ASSERT_EQ(scene.cameras.size(), 1u);
  const NamedCamera& camera = scene.cameras[0];
  expectNear(camera.spec.eye, {1005.9874267578125f, 766.3170776367188f, 953.3455810546875f}, 1e-3f);
  // The direction comes back from eye and look-at points about 1400 units out: float rounding
  // there is about 1e-4 of a unit.
  expectNear(normalize(camera.spec.lookAt - camera.spec.eye),
             -normalize(Vec3f{0.6246951818466187f, 0.4685211479663849f, 0.6246950030326843f}),
             1e-4f);
  expectNear(camera.spec.up,
             normalize(Vec3f{-0.33129435777664185f, 0.883452296257019f, -0.33129459619522095f}),
             1e-4f);
  EXPECT_NEAR(camera.spec.fovDegrees, 0.3143463730812073 * 180 / M_PI, 1e-4);
  EXPECT_FLOAT_EQ(camera.aspectRatio, 1.0f);
  EXPECT_NEAR(camera.znear, 0.05f, 1e-7f);

  // As a scene: the display faces the camera from the line of sight.
  const Scene framed = loadScene(path);
  expectNear(framed.display.normal, -normalize(camera.spec.lookAt - camera.spec.eye), 1e-5f);
  const Vec3f offAxis = cross(framed.display.center - camera.spec.eye,
                              normalize(camera.spec.lookAt - camera.spec.eye));
  EXPECT_LT(length(offAxis), 1e-2f);
}

// Cameras.gltf (the glTF sample): a perspective and an orthographic camera at (0.5, 0.5, 3).
TEST_F(RealModels, SampleCamerasKeepThePerspectiveOne) {
  const Scene scene = load(model("assimp/glTF2/cameras/Cameras.gltf"));
  ASSERT_EQ(scene.cameras.size(), 1u);
  expectNear(scene.cameras[0].spec.eye, {0.5f, 0.5f, 3});
  EXPECT_NEAR(scene.cameras[0].spec.fovDegrees, 0.7 * 180 / M_PI, 1e-4);
  ASSERT_EQ(scene.notes.size(), 1u);
  EXPECT_NE(scene.notes[0].find("1 orthographic camera"), std::string::npos) << scene.notes[0];
}

TEST(Gltf, BadLightsAndColoursAreInputErrors) {
  TempDir dir;
  const std::string good = lightsAndColoursGltf();
  const auto variant = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const std::string path = dir.file("bad.gltf");
  writeFile(path, variant("\"outerConeAngle\": 0.5", "\"outerConeAngle\": 0.1"));
  expectInputError(path, "innerConeAngle");
  writeFile(path, variant("{\"light\": 2}", "{\"light\": 7}"));
  expectInputError(path, "light 7 does not exist");
  writeFile(path, variant("\"type\": \"VEC4\"", "\"type\": \"VEC2\""));
  expectInputError(path, "COLOR_0: must be VEC3 or VEC4");
  writeFile(path, variant("\"yfov\": 0.5", "\"yfov\": 4"));
  expectInputError(path, "yfov");
}

}  // namespace
}  // namespace parallax
