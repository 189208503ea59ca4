// glTF 2.0 (.gltf and .glb): a node hierarchy with a shared mesh, written by the test, and
// assimp's models against the counts and bounds assimp reports.
#include "parallax/importer/mesh_test_support.h"

namespace parallax {
namespace {

using namespace meshtest;

TEST(MeshFile, GltfHierarchyAndSharedMesh) {
  TempDir dir;
  const std::string path = dir.file("scene.gltf");
  writeFile(path, hierarchyGltf());
  const Scene scene = load(path);
  // Both instances share the one material, so they form one mesh; each drops its degenerate
  // triangle, node 4 is not in the scene.
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(droppedCount(scene), 2u);
  // Instance 1: p -> (10,0,0) + 2 p. Instance 2: p -> (10,0,0) + Rz(90)(p + (0,5,0)), where
  // Rz(90)(x, y, z) = (-y, x, z).
  expectTriangles(scene.meshes[0], {{Vec3f(10, 0, 0), Vec3f(12, 0, 0), Vec3f(10, 2, 0)},
                                    {Vec3f(5, 0, 0), Vec3f(5, 1, 0), Vec3f(4, 0, 0)}});
  const TriangleMesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (const Vec3f& n : mesh.normals) expectNear(n, {0, 0, 1});
  // glTF's v runs down the image; ours runs up.
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  EXPECT_EQ(mesh.uvs[mesh.indices[1]].x, 1.0f);
  EXPECT_EQ(mesh.uvs[mesh.indices[1]].y, 1.0f);
  EXPECT_EQ(mesh.uvs[mesh.indices[2]].y, 0.0f);

  ASSERT_EQ(scene.materials.size(), 1u);
  expectNear(scene.materials[0].diffuse, {0.5f, 0.25f, 1});
  expectNear(scene.materials[0].emission, {1, 2, 3});
  EXPECT_EQ(scene.materials[0].diffuseTexture, -1);
}

TEST(MeshFile, GltfUnderMirrorKeepsNormalsAndWindingConsistent) {
  TempDir dir;
  const std::string path = dir.file("scene.gltf");
  writeFile(path, hierarchyGltf());
  MeshLoadOptions options;
  options.worldFromFile = Transform::scale({-1, 1, 1});
  const Scene scene = load(path, options);
  ASSERT_EQ(scene.triangleCount(), 2u);
  const TriangleMesh& mesh = scene.meshes[0];
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    // Shading normals follow the inverse transpose, (0,0,1) stays (0,0,1); the reversed
    // winding keeps the geometric normal on the same side.
    EXPECT_GT(dot(geometricNormal(triangle(mesh, t)), mesh.normals[mesh.indices[3 * t]]), 0.0f);
  }
  EXPECT_EQ(triangle(mesh, 0)[0].x, -10.0f);
}

// Node transforms keep to the scene file's ranges (N75): translations within 1e6 scene units,
// scales within 1e-6 to 1e6 (or 0), matrix entries within 1e6, also composed through the
// parents and in animation keys; each refusal names the node.
TEST(MeshFile, GltfNodeTransformsBeyond1e6AreRefused) {
  TempDir dir;
  const std::string path = dir.file("far.gltf");
  const auto with = [](const std::string& from, const std::string& to) {
    std::string text = hierarchyGltf();
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {with(R"("translation": [10, 0, 0])", R"("translation": [1e30, 0, 0])"),
       "node 0: translation 1e+30 is beyond 1e6 scene units"},
      {with(R"("translation": [10, 0, 0])", R"("translation": [10, -1000001, 0], "name": "far")"),
       "node 0 ('far'): translation -1000001 is beyond 1e6 scene units"},
      {with(R"("scale": [2, 2, 2])", R"("scale": [2, 1e7, 2])"),
       "node 1: scale 1e+07 is not within 1e-6 to 1e6 in size (nor 0)"},
      {with(R"("scale": [2, 2, 2])", R"("scale": [2, 1e-9, 2])"),
       "node 1: scale 1e-09 is not within 1e-6 to 1e6 in size (nor 0)"},
      {with("0,5,0,1]", "0,2e6,0,1]"), "node 3: matrix entry 2e+06 is beyond 1e6 in size"},
      // Each within range, composed beyond it: 10 + 1e6 along x under node 0.
      {with(R"("scale": [2, 2, 2], "mesh": 0})",
            R"("scale": [2, 2, 2], "mesh": 0, "translation": [1000000, 0, 0]})"),
       "node 1: its position composed through its parents lies beyond 1e6 scene units"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected);
    writeFile(path, c.text);
    expectInputError(path, c.expected);
  }
  // At the limits: accepted, and a zero scale hides its node's triangles.
  writeFile(path, with(R"("translation": [10, 0, 0])", R"("translation": [999990, 0, 0])"));
  EXPECT_EQ(load(path).triangleCount(), 2u);
  writeFile(path, with(R"("scale": [2, 2, 2])", R"("scale": [0, 0, 0])"));
  EXPECT_EQ(load(path).triangleCount(), 1u);
}

TEST_F(RealModels, CylinderEngineExpandsSharedMeshes) {
  const Scene scene = load(model("assimp/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"));
  EXPECT_EQ(scene.triangleCount(), 110336u);
  EXPECT_EQ(droppedCount(scene), 11160u);
  EXPECT_EQ(scene.triangleCount() + droppedCount(scene), 121496u);
  expectBounds(scene, {-371.692230f, -180.971558f, -140}, {371.692169f, 92.041565f, 128}, 2e-3f);
}

TEST_F(RealModels, BoxTexturedLoadsItsTexture) {
  const std::string folder = model("assimp/glTF2/BoxTextured-glTF/");
  const Scene scene = load(folder + "BoxTextured.gltf");
  EXPECT_EQ(scene.triangleCount(), 12u);
  expectBounds(scene, Vec3f(-0.5f), Vec3f(0.5f), 1e-6f);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].uvs.size(), scene.meshes[0].positions.size());
  const Material& material = scene.materials[scene.meshes[0].material];
  ASSERT_GE(material.diffuseTexture, 0);
  const Texture& texture = scene.textures[size_t(material.diffuseTexture)];
  ASSERT_EQ(texture.kind, Texture::Kind::Image);
  const Image& image = scene.images[size_t(texture.image)];
  // The PNG's own header (IHDR: big-endian width and height at bytes 16..23) is the truth.
  const std::string png = readFile(folder + "CesiumLogoFlat.png");
  ASSERT_GE(png.size(), 24u);
  auto be32 = [&](size_t at) {
    return int(uint8_t(png[at])) << 24 | int(uint8_t(png[at + 1])) << 16 |
           int(uint8_t(png[at + 2])) << 8 | int(uint8_t(png[at + 3]));
  };
  EXPECT_EQ(image.width(), be32(16));
  EXPECT_EQ(image.height(), be32(20));
  float sum = 0;
  for (const Vec3f& p : image.pixels()) sum += p.x + p.y + p.z;
  EXPECT_GT(sum, 0.0f) << "the texture has content";
}

TEST_F(RealModels, TruncatedGlbIsAnError) {
  TempDir dir;
  const std::string glb =
      readFile(model("assimp/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"));
  writeFile(dir.file("half.glb"), glb.substr(0, glb.size() / 2));
  expectInputError(dir.file("half.glb"), "half.glb");
}

}  // namespace
}  // namespace parallax
