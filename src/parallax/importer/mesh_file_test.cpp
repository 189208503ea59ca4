// loadMeshFile across formats: bad input of every kind fails with an error naming the file
// and leaves the scene unchanged; isMeshFile knows the extensions.
#include "parallax/importer/mesh_test_support.h"

namespace parallax {
namespace {

using namespace meshtest;

// Bad input

TEST(MeshFile, MissingAndEmptyFiles) {
  TempDir dir;
  for (const std::string ext : {".obj", ".ply", ".stl", ".gltf", ".glb"}) {
    expectInputError(dir.file("absent" + ext), "not found");
    writeFile(dir.file("empty" + ext), "");
    expectInputError(dir.file("empty" + ext), "empty");
  }
}

TEST(MeshFile, TruncatedBinaryFiles) {
  TempDir dir;
  const std::array<Vec3f, 3> tri = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)};
  std::string stl = binaryStl("binary", {tri, tri, tri}, 3);
  writeFile(dir.file("cut.stl"), stl.substr(0, stl.size() - 20));
  expectInputError(dir.file("cut.stl"), "truncated");
  // A cut "solid" file is neither valid binary nor valid ASCII: both readings are reported.
  stl = binaryStl("solid x", {tri, tri}, 2);
  writeFile(dir.file("cut_solid.stl"), stl.substr(0, stl.size() - 1));
  expectInputError(dir.file("cut_solid.stl"), "truncated");

  const std::string ply = binaryPly(false);
  writeFile(dir.file("cut.ply"), ply.substr(0, ply.size() - 3));
  expectInputError(dir.file("cut.ply"), "truncated");
  writeFile(dir.file("cut_vertices.ply"), ply.substr(0, ply.find("end_header") + 40));
  expectInputError(dir.file("cut_vertices.ply"), "truncated");

  // A glTF whose index accessor claims more elements than its buffer view holds.
  writeFile(dir.file("cut.gltf"), hierarchyGltf(9));
  expectInputError(dir.file("cut.gltf"), "past the end");
}

TEST(MeshFile, NonFiniteCoordinates) {
  TempDir dir;
  writeFile(dir.file("nan.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
  expectInputError(dir.file("nan.ply"), "vertex 1: coordinate is NaN");

  const float inf = std::numeric_limits<float>::infinity();
  writeFile(dir.file("inf.stl"),
            binaryStl("", {{Vec3f(0, 0, 0), Vec3f(inf, 0, 0), Vec3f(0, 1, 0)}}, 1));
  expectInputError(dir.file("inf.stl"), "vertex 1: coordinate is infinite");

  writeFile(dir.file("nan.obj"), "v 0 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\n");
  expectInputError(dir.file("nan.obj"), "line 2: vertex coordinate is NaN");
}

TEST(MeshFile, IndicesOutOfRange) {
  TempDir dir;
  writeFile(dir.file("far.ply"), binaryPly(false, 1));  // the pentagon's last index becomes 5
  expectInputError(dir.file("far.ply"), "face 0: vertex index 5 is out of range (5 vertices)");

  writeFile(dir.file("far.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n");
  expectInputError(dir.file("far.obj"), "face 1: vertex index 4 is out of range");
  // Relative indices count back from the line they are on; the same message with every
  // tinyobjloader (Debian 12's takes such a file, Debian 13's refuses it with its own words).
  writeFile(dir.file("before.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n");
  expectInputError(dir.file("before.obj"),
                   "line 4: vertex index -4 is out of range (3 defined before it)");
  writeFile(dir.file("ahead.obj"), "v 0 0 0\nf -1 -2 -3\nv 1 0 0\nv 0 1 0\n");
  expectInputError(dir.file("ahead.obj"),
                   "line 2: vertex index -2 is out of range (1 defined before it)");
  writeFile(dir.file("zero.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/0 2/1 3/1\n");
  expectInputError(dir.file("zero.obj"),
                   "line 5: texture coordinate index 0 is out of range (1 defined before it)");
  writeFile(dir.file("fine.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf -3//-1 -2//1 -1//1\n");
  Scene fine;
  loadMeshFile(dir.file("fine.obj"), {}, fine);
  ASSERT_EQ(fine.meshes.size(), 1u);
  EXPECT_EQ(fine.meshes[0].triangleCount(), 1u);

  writeFile(dir.file("far.gltf"), hierarchyGltf(6, 9));
  expectInputError(dir.file("far.gltf"), "vertex index 9 is out of range (4 vertices)");
}

TEST(MeshFile, MalformedText) {
  TempDir dir;
  writeFile(dir.file("bad.stl"), "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n");
  expectInputError(dir.file("bad.stl"), "line 4: expected a number, found 'zero'");
  writeFile(dir.file("short.stl"), "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n");
  expectInputError(dir.file("short.stl"), "the file ends");
  writeFile(dir.file("bad.ply"), "ply\nformat ascii 1.0\nelement vertex 1\nproperty flot x\n");
  expectInputError(dir.file("bad.ply"), "unknown property type 'flot'");
  writeFile(dir.file("bad.gltf"), "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [");
  expectInputError(dir.file("bad.gltf"), "bad.gltf");
  writeFile(dir.file("old.gltf"), R"({"asset": {"version": "1.0"}, "scenes": [], "nodes": []})");
  expectInputError(dir.file("old.gltf"), "version '1.0' is not supported");
  writeFile(dir.file("two.obj"), "v 0 0\nf 1 1 1\n");
  expectInputError(dir.file("two.obj"), "line 1: 'v' needs 3 numbers, found 2");
}

TEST(MeshFile, IsMeshFile) {
  EXPECT_TRUE(isMeshFile("a/b/model.OBJ"));
  EXPECT_TRUE(isMeshFile("x.ply"));
  EXPECT_TRUE(isMeshFile("x.stl"));
  EXPECT_TRUE(isMeshFile("x.gltf"));
  EXPECT_TRUE(isMeshFile("x.glb"));
  EXPECT_FALSE(isMeshFile("scene.json"));
  EXPECT_FALSE(isMeshFile("obj"));
}

}  // namespace
}  // namespace parallax
