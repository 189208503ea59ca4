// Shared by the mesh loader tests (mesh_*_test.cpp): temporary folders, synthetic files with
// known triangles, and the real models fetched by tools/fetch-data, whose expected counts and
// bounds come from assimp, an independent importer.
#pragma once

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
#include "parallax/importer/mesh_file.h"

namespace parallax::meshtest {

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

inline void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  ASSERT_TRUE(out.good()) << path;
}

inline std::string readFile(const std::string& path) {
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

inline Scene load(const std::string& path, const MeshLoadOptions& options = {}) {
  Scene scene;
  loadMeshFile(path, options, scene);
  return scene;
}

// The number in the "<file>: dropped N degenerate triangles" warning; 0 without one.
inline size_t droppedCount(const Scene& scene) {
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

inline void expectNear(const Vec3f& actual, const Vec3f& expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// The corners of triangle t of a mesh.
inline std::array<Vec3f, 3> triangle(const TriangleMesh& mesh, size_t t) {
  return {mesh.positions[mesh.indices[3 * t]], mesh.positions[mesh.indices[3 * t + 1]],
          mesh.positions[mesh.indices[3 * t + 2]]};
}

inline Vec3f geometricNormal(const std::array<Vec3f, 3>& p) {
  return cross(p[1] - p[0], p[2] - p[0]);
}

// Expects the mesh's triangles to be exactly `expected` (as corner lists, in order, each
// allowed to start at any corner but keeping its winding).
inline void expectTriangles(const TriangleMesh& mesh,
                            const std::vector<std::array<Vec3f, 3>>& expected) {
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
inline void expectInputError(const std::string& path, const std::string& expected) {
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

// A pentagon in a binary PLY with a double coordinate, an int8 property and a list in the
// vertex element, written in either byte order.
inline std::string binaryPly(bool bigEndian, uint32_t pentagonIndexShift = 0) {
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

inline std::string base64(const std::string& bytes) {
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
inline std::string hierarchyGltf(size_t indexCount = 6, uint16_t lastIndex = 1) {
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

// Real models, fetched by tools/fetch-data. The expected figures come from assimp 5.2
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

inline std::string dataDir() {
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

inline void expectBounds(const Scene& scene, const Vec3f& lo, const Vec3f& hi, float tolerance) {
  const Bounds3f b = scene.bounds();
  expectNear(b.lo, lo, tolerance);
  expectNear(b.hi, hi, tolerance);
}

inline std::string binaryStl(const std::string& header80,
                             const std::vector<std::array<Vec3f, 3>>& tris, size_t announced) {
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

}  // namespace parallax::meshtest
