// glTF node animation: a file written by the test, whose nodes' channels move a triangle along
// known paths, loaded and posed (scene/motion.h) against the transforms worked out by hand.
#include <cmath>

#include "parallax/importer/mesh_test_support.h"
#include "parallax/scene/motion.h"

namespace parallax {
namespace {

using namespace meshtest;

// Node 0 (at rest translated by (5, 0, 0)) carries node 1 with the triangle (0,0,0), (1,0,0),
// (0,1,0); node 2 holds the same triangle and does not move. Node 0's translation runs from
// (0,0,0) at 0 s to (4,0,0) at 2 s (LINEAR); node 1 turns from the identity to 90 degrees
// about z between 0 and 1 s (`rotationInterpolation`).
std::string animatedGltf(const std::string& rotationInterpolation = "LINEAR") {
  Bytes buffer;
  for (const Vec3f& p : {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)})
    buffer.f32(p.x).f32(p.y).f32(p.z);                        // 0: 36 bytes
  buffer.put(uint16_t(0)).put(uint16_t(1)).put(uint16_t(2));  // 36: 6 bytes
  buffer.put(uint16_t(0));                                    // pad to 44
  buffer.f32(0).f32(2);                                       // 44: translation times
  buffer.f32(0).f32(0).f32(0).f32(4).f32(0).f32(0);           // 52: translation values
  buffer.f32(0).f32(1);                                       // 76: rotation times
  const auto h = float(std::sqrt(0.5));
  buffer.f32(0).f32(0).f32(0).f32(1).f32(0).f32(0).f32(h).f32(h);  // 84: rotation values
  std::ostringstream json;
  json << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 2]}],
  "nodes": [{"translation": [5, 0, 0], "children": [1]}, {"mesh": 0}, {"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "animations": [{"channels": [
      {"sampler": 0, "target": {"node": 0, "path": "translation"}},
      {"sampler": 1, "target": {"node": 1, "path": "rotation"}}],
    "samplers": [{"input": 2, "output": 3, "interpolation": "LINEAR"},
                 {"input": 4, "output": 5, "interpolation": ")"
       << rotationInterpolation << R"("}]}],
  "buffers": [{"byteLength": )"
       << buffer.data.size() << R"(, "uri": "data:application/octet-stream;base64,)"
       << base64(buffer.data) << R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 6},
                  {"buffer": 0, "byteOffset": 44, "byteLength": 8},
                  {"buffer": 0, "byteOffset": 52, "byteLength": 24},
                  {"buffer": 0, "byteOffset": 76, "byteLength": 8},
                  {"buffer": 0, "byteOffset": 84, "byteLength": 32}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
    {"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [2]},
    {"bufferView": 3, "componentType": 5126, "count": 2, "type": "VEC3"},
    {"bufferView": 4, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
    {"bufferView": 5, "componentType": 5126, "count": 2, "type": "VEC4"}]})";
  return json.str();
}

// The moving mesh's corners in its index order.
std::vector<Vec3f> corners(const Scene& scene, uint32_t mesh) {
  std::vector<Vec3f> out;
  for (uint32_t i : scene.meshes[mesh].indices) out.push_back(scene.meshes[mesh].positions[i]);
  return out;
}

void expectCorners(const std::vector<Vec3f>& got, const std::vector<Vec3f>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) expectNear(got[i], want[i], 1e-5f);
}

TEST(GltfAnimation, NodeChannelsMoveTheirMeshAlongTheKeyedPath) {
  TempDir dir;
  const std::string path = dir.file("animated.gltf");
  writeFile(path, animatedGltf());
  const Scene rest = load(path);
  // The animated node's triangle has a mesh of its own; the still one keeps the shared mesh.
  ASSERT_EQ(rest.meshes.size(), 2u);
  ASSERT_EQ(rest.nodeAnimation.meshes.size(), 1u);
  EXPECT_DOUBLE_EQ(rest.nodeAnimation.seconds, 2.0);
  const uint32_t moving = rest.nodeAnimation.meshes[0].mesh;
  // At rest (the nodes' own TRS): node 0 at (5, 0, 0), node 1 unturned.
  expectCorners(corners(rest, moving), {{5, 0, 0}, {6, 0, 0}, {5, 1, 0}});

  const SceneMotion motion = sceneMotion(rest);
  EXPECT_TRUE(motion.movesGeometry());
  Scene posed = rest;
  // t = 1: node 0 at (2, 0, 0); node 1 turned 90 degrees about z: (x, y) -> (-y, x).
  poseScene(rest, motion, 1.0, posed);
  expectCorners(corners(posed, moving), {{2, 0, 0}, {2, 1, 0}, {1, 0, 0}});
  // t = 0.5: (1, 0, 0) and 45 degrees (the slerp's half-way).
  const auto h = float(std::sqrt(0.5));
  poseScene(rest, motion, 0.5, posed);
  expectCorners(corners(posed, moving), {{1, 0, 0}, {1 + h, h, 0}, {1 - h, h, 0}});
  // After the last key the channels hold: (4, 0, 0), 90 degrees.
  poseScene(rest, motion, 7.0, posed);
  expectCorners(corners(posed, moving), {{4, 0, 0}, {4, 1, 0}, {3, 0, 0}});
  // The still node's mesh never moves.
  const uint32_t still = 1 - moving;
  EXPECT_EQ(posed.meshes[still].positions, rest.meshes[still].positions);
}

TEST(GltfAnimation, StepKeysHoldAndTheLoadTransformAppliesOnTop) {
  TempDir dir;
  const std::string path = dir.file("animated.gltf");
  writeFile(path, animatedGltf("STEP"));
  MeshLoadOptions options;
  options.worldFromFile = Transform::scale({2, 2, 2});
  const Scene rest = load(path, options);
  ASSERT_EQ(rest.nodeAnimation.meshes.size(), 1u);
  const uint32_t moving = rest.nodeAnimation.meshes[0].mesh;
  Scene posed = rest;
  // t = 0.5 with STEP rotation keys: still the first key (no turn); translation (1, 0, 0).
  poseScene(rest, sceneMotion(rest), 0.5, posed);
  expectCorners(corners(posed, moving), {{2, 0, 0}, {4, 0, 0}, {2, 2, 0}});
}

TEST(GltfAnimation, BadChannelsAreErrorsNamingTheFile) {
  TempDir dir;
  const std::string path = dir.file("bad.gltf");
  std::string text = animatedGltf();
  const std::string target = R"("node": 1, "path": "rotation")";
  text.replace(text.find(target), target.size(), R"("node": 9, "path": "rotation")");
  writeFile(path, text);
  expectInputError(path, "target node 9");
}

}  // namespace
}  // namespace parallax
