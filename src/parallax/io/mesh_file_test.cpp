// Tests of loadMeshFile. Synthetic files are written by the tests, so the expected triangles
// are known by construction; real models (fetched by tools/fetch-data) are checked against
// the counts and bounds that assimp, an independent importer, reports for them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "parallax/core/error.h"
#include "parallax/io/mesh_file.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("parallax_mesh_" + std::string(test->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  ASSERT_TRUE(out.good()) << path;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Little- and big-endian binary writers for the synthetic binary files.
struct Bytes {
  std::string data;
  bool bigEndian = false;
  template <typename T>
  Bytes& put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (bigEndian) std::reverse(raw, raw + sizeof(T));
    data.append(raw, sizeof(T));
    return *this;
  }
  Bytes& f32(float v) { return put(v); }
  Bytes& u32(uint32_t v) { return put(v); }
};

Scene load(const std::string& path, const MeshLoadOptions& options = {}) {
  Scene scene;
  loadMeshFile(path, options, scene);
  return scene;
}

// The number in the "<file>: dropped N degenerate triangles" warning; 0 without one.
size_t droppedCount(const Scene& scene) {
  size_t total = 0, warnings = 0;
  const std::string marker = ": dropped ";
  for (const std::string& w : scene.warnings) {
    const size_t at = w.rfind(marker);
    if (at == std::string::npos || w.find(" degenerate triangle", at) == std::string::npos)
      continue;
    total += std::stoul(w.substr(at + marker.size()));
    ++warnings;
  }
  EXPECT_LE(warnings, 1u) << "at most one degenerate-triangle warning per file";
  return total;
}

void expectNear(const Vec3f& actual, const Vec3f& expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// The corners of triangle t of a mesh.
std::array<Vec3f, 3> triangle(const TriangleMesh& mesh, size_t t) {
  return {mesh.positions[mesh.indices[3 * t]], mesh.positions[mesh.indices[3 * t + 1]],
          mesh.positions[mesh.indices[3 * t + 2]]};
}

Vec3f geometricNormal(const std::array<Vec3f, 3>& p) {
  return cross(p[1] - p[0], p[2] - p[0]);
}

// Expects the mesh's triangles to be exactly `expected` (as corner lists, in order, each
// allowed to start at any corner but keeping its winding).
void expectTriangles(const TriangleMesh& mesh, const std::vector<std::array<Vec3f, 3>>& expected) {
  ASSERT_EQ(mesh.triangleCount(), expected.size());
  for (size_t t = 0; t < expected.size(); ++t) {
    const auto actual = triangle(mesh, t);
    bool matched = false;
    for (int shift = 0; shift < 3 && !matched; ++shift) {
      bool all = true;
      for (int k = 0; k < 3; ++k)
        all = all && length(actual[size_t((k + shift) % 3)] - expected[t][size_t(k)]) < 1e-5f;
      matched = all;
    }
    EXPECT_TRUE(matched) << "triangle " << t << " is (" << actual[0].x << " " << actual[0].y << " "
                         << actual[0].z << ") (" << actual[1].x << " " << actual[1].y << " "
                         << actual[1].z << ") (" << actual[2].x << " " << actual[2].y << " "
                         << actual[2].z << ")";
  }
}

// Runs `load` on a bad file and returns the error, failing if none is thrown or it does not
// name the file and contain `expected`.
void expectInputError(const std::string& path, const std::string& expected) {
  Scene scene;
  try {
    loadMeshFile(path, {}, scene);
    ADD_FAILURE() << path << ": no InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(fs::path(path).filename().string()), std::string::npos) << what;
    EXPECT_NE(what.find(expected), std::string::npos)
        << "'" << what << "' lacks '" << expected << "'";
    EXPECT_EQ(e.file(), path);
  }
  EXPECT_TRUE(scene.meshes.empty()) << "a failed load must leave the scene unchanged";
  EXPECT_TRUE(scene.materials.empty());
}

// ---------------------------------------------------------------------------------------
// PLY

TEST(MeshFile, AsciiPlyWithExtraElementsAndProperties) {
  TempDir dir;
  const std::string path = dir.file("square.ply");
  // A unit square as one quad, plus a triangle whose corners 0 and 4 coincide (zero area) and
  // one that repeats index 0: both degenerate. The edge element, the vertex list property and
  // the face properties around vertex_indices must be read past.
  writeFile(path,
            "ply\n"
            "format ascii 1.0\n"
            "comment made by hand\n"
            "Made by hand, without the comment keyword\n"
            "element vertex 5\n"
            "property float x\n"
            "property float y\n"
            "property float z\n"
            "property list uchar int tags\n"
            "property float nx\n"
            "property float ny\n"
            "property float nz\n"
            "property float s\n"
            "property float t\n"
            "element edge 1\n"
            "property int vertex1\n"
            "property int vertex2\n"
            "element face 3\n"
            "property uchar flags\n"
            "property list uchar int vertex_indices\n"
            "property list uchar float texcoord\n"
            "end_header\n"
            "0 0 0  2 7 8  0 0 2  0 0\n"
            "1 0 0  0      0 0 2  1 0\n"
            "1 1 0  1 9    0 0 2  1 1\n"
            "0 1 0  0      0 0 2  0 1\n"
            "0 0 0  0      0 0 2  0 0\n"
            "0 1\n"
            "5 4 0 1 2 3  2 0.5 0.5\n"
            "5 3 0 4 1    0\n"
            "5 3 0 0 2    1 3.0\n");
  const Scene scene = load(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.meshes[0];
  // A quad becomes the fan (0 1 2), (0 2 3).
  expectTriangles(mesh, {{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 1, 0)},
                         {Vec3f(0, 0, 0), Vec3f(1, 1, 0), Vec3f(0, 1, 0)}});
  EXPECT_EQ(droppedCount(scene), 2u);
  EXPECT_EQ(scene.warnings.size(), 2u) << "one for the odd header line, one for the drops";
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (const Vec3f& n : mesh.normals) expectNear(n, {0, 0, 1});  // normalised from (0 0 2)
  ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    EXPECT_EQ(mesh.uvs[i].x, mesh.positions[i].x);  // s, t equal x, y by construction
    EXPECT_EQ(mesh.uvs[i].y, mesh.positions[i].y);
  }
  // No material in the file: one default grey material.
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(mesh.material, 0u);
  expectNear(scene.materials[0].diffuse, Vec3f(0.7f));
}

TEST(MeshFile, AsciiPlyWithTheShortestPossibleData) {
  TempDir dir;
  const std::string path = dir.file("tiny.ply");
  // One-character values, all on one line and no final newline: ASCII PLY is a token stream.
  writeFile(path,
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0 1 0 0 0 1 0 3 0 1 2");
  const Scene scene = load(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  expectTriangles(scene.meshes[0], {{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)}});
}

// A pentagon in a binary PLY with a double coordinate, an int8 property and a list in the
// vertex element, written in either byte order.
std::string binaryPly(bool bigEndian, uint32_t pentagonIndexShift = 0) {
  Bytes body;
  body.bigEndian = bigEndian;
  const std::string header = std::string("ply\nformat ") +
                             (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                             " 1.0\n"
                             "element vertex 5\n"
                             "property double x\n"
                             "property char flag\n"
                             "property float y\n"
                             "property list ushort uchar ring\n"
                             "property float z\n"
                             "element face 1\n"
                             "property list uchar uint vertex_index\n"
                             "end_header\n";
  for (int i = 0; i < 5; ++i) {
    const double angle = 2 * 3.14159265358979 * i / 5;
    body.put(std::cos(angle)).put(int8_t(-3)).f32(float(std::sin(angle)));
    body.put(uint16_t(2)).put(uint8_t(1)).put(uint8_t(2));
    body.f32(7.0f);
  }
  body.put(uint8_t(5));
  for (uint32_t i = 0; i < 5; ++i) body.u32(i + pentagonIndexShift);
  return header + body.data;
}

TEST(MeshFile, BinaryPlyBothByteOrdersWithTransform) {
  TempDir dir;
  for (bool bigEndian : {false, true}) {
    const std::string path = dir.file(bigEndian ? "be.ply" : "le.ply");
    writeFile(path, binaryPly(bigEndian));
    MeshLoadOptions options;
    options.worldFromFile = Transform::translate({1, 2, 3}) * Transform::scale(Vec3f(2.0f));
    const Scene scene = load(path, options);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(droppedCount(scene), 0u);
    // The pentagon's fan: (0 1 2), (0 2 3), (0 3 4), each corner at 2 p + (1, 2, 3).
    std::vector<std::array<Vec3f, 3>> expected;
    auto corner = [](int i) {
      const double angle = 2 * 3.14159265358979 * i / 5;
      return Vec3f(float(2 * std::cos(angle) + 1), float(2 * std::sin(angle) + 2), 17.0f);
    };
    for (int k = 1; k <= 3; ++k) expected.push_back({corner(0), corner(k), corner(k + 1)});
    expectTriangles(scene.meshes[0], expected);
    EXPECT_TRUE(scene.meshes[0].normals.empty());
  }
}

// ---------------------------------------------------------------------------------------
// STL

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
  const Scene scene = load(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  expectTriangles(scene.meshes[0], {{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)},
                                    {Vec3f(0, 0, 0), Vec3f(0, 1, 0), Vec3f(0, 0, -15)}});
  EXPECT_EQ(droppedCount(scene), 1u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0], path + ": dropped 1 degenerate triangle");
}

std::string binaryStl(const std::string& header80, const std::vector<std::array<Vec3f, 3>>& tris,
                      size_t announced) {
  Bytes b;
  std::string header = header80;
  header.resize(80, ' ');
  b.data = header;
  b.u32(uint32_t(announced));
  for (const auto& t : tris) {
    b.f32(0).f32(0).f32(0);
    for (const Vec3f& p : t) b.f32(p.x).f32(p.y).f32(p.z);
    b.put(uint16_t(0));
  }
  return b.data;
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
  const Scene scene = load(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  expectTriangles(scene.meshes[0], {tris[0], tris[2]});
  EXPECT_EQ(droppedCount(scene), 1u);
}

TEST(MeshFile, MirroringTransformKeepsFacesOutward) {
  TempDir dir;
  const std::string path = dir.file("tri.stl");
  const std::array<Vec3f, 3> tri = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)};
  writeFile(path, binaryStl("", {tri}, 1));
  MeshLoadOptions options;
  options.worldFromFile = Transform::scale({1, 1, -1});  // a mirror: swaps handedness
  const Scene scene = load(path, options);
  ASSERT_EQ(scene.triangleCount(), 1u);
  // The front side was +z; mirrored in z it faces -z, which needs the winding reversed
  // (the corners alone, mirrored, would still wind counter-clockwise about +z).
  const Vec3f n = geometricNormal(triangle(scene.meshes[0], 0));
  EXPECT_LT(n.z, 0.0f);
}

// ---------------------------------------------------------------------------------------
// OBJ

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

// ---------------------------------------------------------------------------------------
// glTF

std::string base64(const std::string& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t group = 0;
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    for (size_t k = 0; k < 3; ++k) group = group << 8 | (k < n ? uint8_t(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? alphabet[(group >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// One mesh (a right triangle in z = 0 plus a degenerate triangle, with normals +z and UVs)
// used by two nodes of the scene, and by a third node outside it:
//   node 0: translation (10, 0, 0), children 1 and 2
//   node 1: scale 2, mesh 0
//   node 2: rotation 90 degrees about +z, child 3
//   node 3: matrix translating by (0, 5, 0), mesh 0
//   node 4: mesh 0, in no scene
std::string hierarchyGltf(size_t indexCount = 6, uint16_t lastIndex = 1) {
  Bytes buffer;
  const Vec3f positions[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}};
  for (const Vec3f& p : positions) buffer.f32(p.x).f32(p.y).f32(p.z);
  for (int i = 0; i < 4; ++i) buffer.f32(0).f32(0).f32(1);
  const float uvs[4][2] = {{0, 0}, {1, 0}, {0, 1}, {0, 0}};
  for (const auto& uv : uvs) buffer.f32(uv[0]).f32(uv[1]);
  for (uint16_t i : {uint16_t(0), uint16_t(1), uint16_t(2), uint16_t(0), uint16_t(3), lastIndex})
    buffer.put(i);
  const double s = std::sqrt(0.5);
  std::ostringstream json;
  json << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [
    {"translation": [10, 0, 0], "children": [1, 2]},
    {"scale": [2, 2, 2], "mesh": 0},
    {"rotation": [0, 0, )"
       << s << ", " << s << R"(], "children": [3]},
    {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,5,0,1], "mesh": 0},
    {"mesh": 0}],
  "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1,
    "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
  "materials": [{"name": "paint", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 1]},
    "emissiveFactor": [1, 2, 3]}],
  "buffers": [{"byteLength": )"
       << buffer.data.size() << R"(, "uri": "data:application/octet-stream;base64,)"
       << base64(buffer.data) << R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 96, "byteLength": 32},
                  {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": )"
       << indexCount << R"(, "type": "SCALAR"}]})";
  return json.str();
}

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

// ---------------------------------------------------------------------------------------
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
  writeFile(dir.file("before.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n");
  expectInputError(dir.file("before.obj"), "out of range");

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

// ---------------------------------------------------------------------------------------
// Real models, fetched by tools/fetch-data. The expected figures come from assimp 5.2.5
// (Debian package assimp-utils), an independent importer, run in the data folder:
//
//   assimp info FILE -ptv            PreTransformVertices only: every mesh instanced once per
//                                    node and moved to world space. "Faces" counts all
//                                    triangles, degenerate ones included; "Minimum/Maximum
//                                    point" are the bounds.
//   assimp info FILE -ptv -fd -sbpt  adds FindDegenerates and SortByPType: triangles with
//                                    coincident corners become lines or points, so the
//                                    per-mesh "triangle" faces are the ones we keep.
//   assimp info FILE -tri            triangulates OBJ polygons.
//
// Spider_*.stl:      1368 faces = 1312 triangles + 28 lines + 28 points,
//                    bounds (-3.114895 -4 -1.649329) .. (3.114895 4 1.649329)
// 2CylinderEngine:   121496 faces = 110336 triangles + 11160 lines,
//                    bounds (-371.692230 -180.971558 -140) .. (371.692169 92.041565 128)
// bunny.obj:         69666 faces, all triangles,
//                    bounds (-1 -0.991233 -0.775047) .. (1 0.991233 0.775047)
// cornell_box.obj:   18 quads, 36 triangles with -tri, in 4 meshes (one per material used),
//                    bounds (0 0 0) .. (556 548.799988 559.200012)
// BoxTextured.gltf:  12 triangles, bounds (-0.5 -0.5 -0.5) .. (0.5 0.5 0.5)

std::string dataDir() {
  if (const char* env = std::getenv("PARALLAX_DATA_DIR"); env && *env) return env;
  return PARALLAX_DATA_DIR;
}

class RealModels : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(dataDir() + "/bunny.obj") ||
        !fs::exists(dataDir() + "/assimp/STL/Spider_ascii.stl"))
      FAIL() << "test models not found in " << dataDir() << "; run tools/fetch-data";
  }
  static std::string model(const std::string& name) { return dataDir() + "/" + name; }
};

void expectBounds(const Scene& scene, const Vec3f& lo, const Vec3f& hi, float tolerance) {
  const Bounds3f b = scene.bounds();
  expectNear(b.lo, lo, tolerance);
  expectNear(b.hi, hi, tolerance);
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

TEST_F(RealModels, SpiderBinaryAndAsciiAgree) {
  const Scene binary = load(model("assimp/STL/Spider_binary.stl"));
  const Scene ascii = load(model("assimp/STL/Spider_ascii.stl"));
  for (const Scene* scene : {&binary, &ascii}) {
    EXPECT_EQ(scene->triangleCount(), 1312u);
    EXPECT_EQ(droppedCount(*scene), 56u);
    EXPECT_EQ(scene->triangleCount() + droppedCount(*scene), 1368u);
    expectBounds(*scene, {-3.114895f, -4, -1.649329f}, {3.114895f, 4, 1.649329f}, 1e-5f);
  }
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
