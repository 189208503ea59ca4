// STL (ASCII and binary): synthetic files, and assimp's Spider model in both encodings
// against the counts assimp reports.
#include "parallax/importer/mesh_test_support.h"

namespace parallax {
namespace {

using namespace meshtest;

// The file's own axes: STL is Z-up and loadMeshFile turns it Y-up by default
// (mesh_import_test.cpp tests the turn); these tests check what the reader reads.
MeshLoadOptions fileAxes() {
  MeshLoadOptions options;
  options.up = UpAxis::Y;
  return options;
}

TEST(MeshFile, AsciiStl) {
  TempDir dir;
  const std::string path = dir.file("part.stl");
  writeFile(path,
            "solid my part\n"
            "  facet normal 0 0 1\n    outer loop\n"
            "      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
            "    endloop\n  endfacet\n"
            "  facet normal 0 0 0\n    outer loop\n"  // collinear corners: zero area
            "      vertex 0 0 0\n      vertex 1 1 1\n      vertex 2 2 2\n"
            "    endloop\n  endfacet\n"
            "  facet normal 1 0 0\n    outer loop\n"
            "      vertex 0 0 0\n      vertex 0 1 0\n      vertex 0 0 -1.5e1\n"
            "    endloop\n  endfacet\n"
            "endsolid my part\n");
  const Scene scene = load(path, fileAxes());
  ASSERT_EQ(scene.meshes.size(), 1u);
  expectTriangles(scene.meshes[0], {{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)},
                                    {Vec3f(0, 0, 0), Vec3f(0, 1, 0), Vec3f(0, 0, -15)}});
  EXPECT_EQ(droppedCount(scene), 1u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0], path + ": dropped 1 degenerate triangle");
}

TEST(MeshFile, BinaryStlStartingWithSolid) {
  TempDir dir;
  const std::string path = dir.file("binary.stl");
  // The header starts with "solid", as some exporters write: the size check must win.
  const std::vector<std::array<Vec3f, 3>> tris = {
      {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)},
      {Vec3f(5, 5, 5), Vec3f(5, 5, 5), Vec3f(6, 5, 5)},  // repeated corner
      {Vec3f(0, 0, 1), Vec3f(0, 2, 1), Vec3f(-3, 0, 1)}};
  writeFile(path, binaryStl("solid exported by a careless tool", tris, tris.size()));
  const Scene scene = load(path, fileAxes());
  ASSERT_EQ(scene.meshes.size(), 1u);
  expectTriangles(scene.meshes[0], {tris[0], tris[2]});
  EXPECT_EQ(droppedCount(scene), 1u);
}

TEST(MeshFile, MirroringTransformKeepsFacesOutward) {
  TempDir dir;
  const std::string path = dir.file("tri.stl");
  const std::array<Vec3f, 3> tri = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)};
  writeFile(path, binaryStl("", {tri}, 1));
  MeshLoadOptions options = fileAxes();
  options.worldFromFile = Transform::scale({1, 1, -1});  // a mirror: swaps handedness
  const Scene scene = load(path, options);
  ASSERT_EQ(scene.triangleCount(), 1u);
  // The front side was +z; mirrored in z it faces -z, which needs the winding reversed
  // (the corners alone, mirrored, would still wind counter-clockwise about +z).
  const Vec3f n = geometricNormal(triangle(scene.meshes[0], 0));
  EXPECT_LT(n.z, 0.0f);
}

TEST_F(RealModels, SpiderBinaryAndAsciiAgree) {
  const Scene binary = load(model("assimp/STL/Spider_binary.stl"), fileAxes());
  const Scene ascii = load(model("assimp/STL/Spider_ascii.stl"), fileAxes());
  for (const Scene* scene : {&binary, &ascii}) {
    EXPECT_EQ(scene->triangleCount(), 1312u);
    EXPECT_EQ(droppedCount(*scene), 56u);
    EXPECT_EQ(scene->triangleCount() + droppedCount(*scene), 1368u);
    expectBounds(*scene, {-3.114895f, -4, -1.649329f}, {3.114895f, 4, 1.649329f}, 1e-5f);
  }
}

}  // namespace
}  // namespace parallax
