// OBJ with MTL: synthetic files (quads, negative indices, materials, concave faces), and the
// bunny and the Cornell box against the counts and bounds assimp reports.
#include "parallax/importer/mesh_test_support.h"

namespace parallax {
namespace {

using namespace meshtest;

// The analytic sRGB decoding (IEC 61966-2-1) of an 8-bit code.
float srgbDecode(int code) {
  const double c = code / 255.0;
  return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

TEST(MeshFile, ObjQuadsNegativeIndicesAndMaterials) {
  TempDir dir;
  const std::string path = dir.file("room.obj");
  fs::create_directories(dir.file("textures"));
  // A 2x1 binary PPM: stb_image reads it like any other 8-bit sRGB image.
  const char pixels[] = {'\x80', '\x00', '\xff', '\x10', '\x20', '\x30'};
  writeFile(dir.file("textures/wall.ppm"), "P6\n2 1\n255\n" + std::string(pixels, sizeof pixels));
  writeFile(dir.file("room.mtl"),
            "newmtl wall\nKd 1 0.5 0.25\nmap_Kd textures/wall.ppm\n"
            "newmtl lamp\nKd 0 0 0\nKe 5 6 7\n"
            "newmtl chrome\nKd 0.1 0.1 0.1\nKs 0.9 0.8 0.7\nillum 3\n"
            "newmtl unused\nKd 0 1 0\n");
  writeFile(path,
            "mtllib room.mtl\n"
            "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "usemtl wall\n"
            "f -4/-4 -3/-3 -2/-2 -1/-1\n"  // a quad by relative indices
            "o lamp\n"
            "v 0 0 3\nv 1 0 3\nv 1 1 3\nv 0 1 3\nv 0.5 1.5 3\n"
            "usemtl lamp\n"
            "f -5 -4 -3 -1 -2\n"  // a pentagon (0 0)(1 0)(1 1)(0.5 1.5)(0 1): fan of 3
            "f 5 6 6\n"           // repeated vertex
            "usemtl chrome\n"
            "f 1 2 9\n");
  const Scene scene = load(path);
  EXPECT_EQ(droppedCount(scene), 1u);
  ASSERT_EQ(scene.meshes.size(), 3u);
  ASSERT_EQ(scene.materials.size(), 3u) << "only the materials in use are added";

  const TriangleMesh* wall = nullptr;
  const TriangleMesh* lamp = nullptr;
  const TriangleMesh* chrome = nullptr;
  for (const TriangleMesh& m : scene.meshes) {
    const std::string& name = scene.materials[m.material].name;
    (name == "wall" ? wall : name == "lamp" ? lamp : chrome) = &m;
  }
  ASSERT_TRUE(wall && lamp && chrome);
  EXPECT_EQ(wall->name, "room/wall");

  // The quad: two triangles covering the 2x1 rectangle, with the UVs of their corners.
  ASSERT_EQ(wall->triangleCount(), 2u);
  float area = 0;
  for (size_t t = 0; t < 2; ++t) area += 0.5f * length(geometricNormal(triangle(*wall, t)));
  EXPECT_FLOAT_EQ(area, 2.0f);
  ASSERT_EQ(wall->uvs.size(), wall->positions.size());
  for (size_t i = 0; i < wall->positions.size(); ++i) {
    EXPECT_EQ(wall->uvs[i].x, wall->positions[i].x / 2);
    EXPECT_EQ(wall->uvs[i].y, wall->positions[i].y);
  }
  const Material& wallMaterial = scene.materials[wall->material];
  expectNear(wallMaterial.diffuse, {1, 0.5f, 0.25f});
  ASSERT_GE(wallMaterial.diffuseTexture, 0);
  const Texture& texture = scene.textures[size_t(wallMaterial.diffuseTexture)];
  EXPECT_EQ(texture.kind, Texture::Kind::Image);
  const Image& image = scene.images[size_t(texture.image)];
  ASSERT_EQ(image.width(), 2);
  ASSERT_EQ(image.height(), 1);
  expectNear(image.at(0, 0), {srgbDecode(0x80), 0, 1});
  expectNear(image.at(1, 0), {srgbDecode(0x10), srgbDecode(0x20), srgbDecode(0x30)});

  expectTriangles(*lamp, {{Vec3f(0, 0, 3), Vec3f(1, 0, 3), Vec3f(1, 1, 3)},
                          {Vec3f(0, 0, 3), Vec3f(1, 1, 3), Vec3f(0.5f, 1.5f, 3)},
                          {Vec3f(0, 0, 3), Vec3f(0.5f, 1.5f, 3), Vec3f(0, 1, 3)}});
  expectNear(scene.materials[lamp->material].emission, {5, 6, 7});

  expectTriangles(*chrome, {{Vec3f(0, 0, 0), Vec3f(2, 0, 0), Vec3f(0.5f, 1.5f, 3)}});
  expectNear(scene.materials[chrome->material].mirror, {0.9f, 0.8f, 0.7f});
}

TEST(MeshFile, ConcavePolygonsAreSplitInsideTheirOutline) {
  TempDir dir;
  const std::string path = dir.file("ell.obj");
  // An L of area 3 whose first corner (2,1) cannot see the corner (1,2): a fan from it would
  // fold over. At z = 0 it winds counter-clockwise about +z, at z = 1 the reverse way.
  const char* ell[6] = {"2 1", "1 1", "1 2", "0 2", "0 0", "2 0"};
  std::string obj;
  for (const char* z : {"0", "1"})
    for (const char* xy : ell) obj += std::string("v ") + xy + " " + z + "\n";
  obj += "f 1 2 3 4 5 6\nf 12 11 10 9 8 7\n";
  writeFile(path, obj);
  const Scene scene = load(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.triangleCount(), 8u);
  float area[2] = {0, 0};
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const auto corners = triangle(mesh, t);
    const int z = int(corners[0].z);
    const Vec3f n = geometricNormal(corners);
    EXPECT_GT(z == 0 ? n.z : -n.z, 0.0f) << "triangle " << t << " keeps the polygon's winding";
    area[z] += 0.5f * length(n);
  }
  EXPECT_FLOAT_EQ(area[0], 3.0f);
  EXPECT_FLOAT_EQ(area[1], 3.0f);
}

TEST(MeshFile, MaterialOverrideAddsNoMaterials) {
  TempDir dir;
  const std::string path = dir.file("tri.obj");
  writeFile(dir.file("tri.mtl"), "newmtl red\nKd 1 0 0\n");
  writeFile(path, "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
  Scene scene;
  scene.materials.resize(3);
  MeshLoadOptions options;
  options.materialOverride = 2;
  options.name = "thing";
  loadMeshFile(path, options, scene);
  EXPECT_EQ(scene.materials.size(), 3u);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].material, 2u);
  EXPECT_EQ(scene.meshes[0].name, "thing");
}

TEST_F(RealModels, Bunny) {
  const Scene scene = load(model("bunny.obj"));
  EXPECT_EQ(scene.triangleCount(), 69666u);
  EXPECT_EQ(droppedCount(scene), 0u);
  expectBounds(scene, {-1, -0.991233f, -0.775047f}, {1, 0.991233f, 0.775047f}, 1e-5f);
}

TEST_F(RealModels, CornellBox) {
  const Scene scene = load(model("cornell_box.obj"));
  EXPECT_EQ(scene.triangleCount(), 36u);
  EXPECT_EQ(scene.meshes.size(), 4u);
  expectBounds(scene, {0, 0, 0}, {556, 548.799988f, 559.200012f}, 1e-3f);
  for (const TriangleMesh& mesh : scene.meshes) {
    const Material& material = scene.materials[mesh.material];
    // cornell_box.mtl: red is Kd 1 0 0, green Kd 0 1 0, white and light Kd 1 1 1.
    if (material.name == "red") expectNear(material.diffuse, {1, 0, 0});
    if (material.name == "green") expectNear(material.diffuse, {0, 1, 0});
    if (material.name == "white") {
      EXPECT_EQ(mesh.triangleCount(), 30u);
    }
  }
}

}  // namespace
}  // namespace parallax
