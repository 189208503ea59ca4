// Vertex colours from PLY (8-bit sRGB codes) and OBJ ("v x y z r g b", sRGB in [0, 1]) against
// the sRGB decoding written out here (IEC 61966-2-1); the Cornell box's lamp (MTL "Ka 20 20
// 20", no Ke) emitting and lighting the box.
#include "parallax/importer/mesh_test_support.h"
#include "parallax/importer/scene_file.h"
#include "parallax/scene/light_checks.h"

namespace parallax {
namespace {

using namespace meshtest;

double srgbToLinearReference(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

Vec3f decoded(double r, double g, double b) {
  return {float(srgbToLinearReference(r)), float(srgbToLinearReference(g)),
          float(srgbToLinearReference(b))};
}

TEST(VertexColours, PlyRedGreenBlueAreSrgbCodes) {
  TempDir dir;
  const std::string path = dir.file("tri.ply");
  writeFile(path,
            "ply\nformat ascii 1.0\nelement vertex 3\n"
            "property float x\nproperty float y\nproperty float z\n"
            "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0 255 0 0 255\n"
            "1 0 0 10 128 200 255\n"
            "0 1 0 0 0 0 255\n"
            "3 0 1 2\n");
  const Scene scene = load(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.colors.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    const Vec3f p = mesh.positions[i];
    const Vec3f expected = p.x == 1   ? decoded(10 / 255.0, 128 / 255.0, 200 / 255.0)
                           : p.y == 1 ? Vec3f(0.0f)
                                      : Vec3f(1, 0, 0);
    expectNear(mesh.colors[i], expected, 1e-6f);
  }
  // A file without colour properties gives no colours.
  writeFile(path,
            "ply\nformat ascii 1.0\nelement vertex 3\n"
            "property float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_TRUE(load(path).meshes.at(0).colors.empty());
}

TEST(VertexColours, ObjColoursOnlyWhenEveryVertexHasThem) {
  TempDir dir;
  const std::string path = dir.file("tri.obj");
  writeFile(path, "v 0 0 0 1 0 0\nv 1 0 0 0.5 0.25 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
  const Scene scene = load(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.colors.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    const Vec3f p = mesh.positions[i];
    const Vec3f expected = p.x == 1   ? decoded(0.5, 0.25, 0)
                           : p.y == 1 ? Vec3f(0, 0, 1)
                                      : Vec3f(1, 0, 0);
    expectNear(mesh.colors[i], expected, 1e-6f);
  }
  writeFile(path, "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(load(path).meshes.at(0).colors.empty());
  writeFile(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(load(path).meshes.at(0).colors.empty());
}

TEST(VertexColours, NonFiniteColoursAreInputErrors) {
  TempDir dir;
  const std::string path = dir.file("tri.ply");
  writeFile(path,
            "ply\nformat ascii 1.0\nelement vertex 3\n"
            "property float x\nproperty float y\nproperty float z\n"
            "property float red\nproperty float green\nproperty float blue\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0 1 0 0\n1 0 0 nan 0 0\n0 1 0 0 0 1\n3 0 1 2\n");
  expectInputError(path, "vertex 1: colour is not finite");
}

// An MTL Ke makes its faces an area light of a bare OBJ, in place of the default key light.
TEST(MtlEmission, KeMakesAMeshLight) {
  TempDir dir;
  writeFile(dir.file("lamp.mtl"), "newmtl lamp\nKd 0 0 0\nKe 5 4 3\nnewmtl floor\nKd 1 1 1\n");
  writeFile(dir.file("lamp.obj"),
            "mtllib lamp.mtl\n"
            "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n"
            "v 0 1 0\nv 0 1 1\nv 1 1 1\nv 1 1 0\n"
            "usemtl floor\nf 1 4 3 2\n"   // faces +y
            "usemtl lamp\nf 5 8 7 6\n");  // faces -y, toward the floor
  const Scene scene = loadScene(dir.file("lamp.obj"));
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].kind, Light::Kind::Mesh);
  expectNear(scene.lights[0].intensity, {5, 4, 3});
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  // Turned the other way, it lights nothing, and loadScene says so.
  std::string obj = readFile(dir.file("lamp.obj"));
  obj.replace(obj.find("f 5 8 7 6"), 9, "f 5 6 7 8");
  writeFile(dir.file("lamp.obj"), obj);
  const Scene flipped = loadScene(dir.file("lamp.obj"));
  ASSERT_EQ(flipped.warnings.size(), 1u);
  EXPECT_NE(flipped.warnings[0].find("lights nothing"), std::string::npos) << flipped.warnings[0];
}

// cornell_box.mtl gives its lamp "Ka 20 20 20" and no Ke: read as emission, the lamp becomes a
// mesh light, it faces into the box (no facing-away warning), and no default key light is
// added.
TEST_F(RealModels, CornellBoxLampEmits) {
  const Scene scene = loadScene(model("cornell_box.obj"));
  int lamps = 0;
  for (const Light& light : scene.lights) {
    ASSERT_EQ(light.kind, Light::Kind::Mesh);
    expectNear(light.intensity, Vec3f(20.0f));
    EXPECT_EQ(scene.materials[scene.meshes[size_t(light.mesh)].material].name, "light");
    ++lamps;
  }
  EXPECT_EQ(lamps, 1);
  EXPECT_EQ(scene.ambient, Vec3f(0.0f));
  EXPECT_TRUE(lightFacingWarnings(scene).empty());
  EXPECT_TRUE(std::any_of(scene.warnings.begin(), scene.warnings.end(), [](const std::string& w) {
    return w.find("reading Ka as its emission") != std::string::npos;
  }));
}

}  // namespace
}  // namespace parallax
