// PLY (ASCII and binary, both byte orders): synthetic files whose triangles are known by
// construction.
#include "parallax/importer/mesh_test_support.h"

namespace parallax {
namespace {

using namespace meshtest;

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

TEST(MeshFile, BinaryPlyBothByteOrdersWithTransform) {
  TempDir dir;
  for (bool bigEndian : {false, true}) {
    const std::string path = dir.file(bigEndian ? "be.ply" : "le.ply");
    writeFile(path, binaryPly(bigEndian));
    MeshLoadOptions options;
    options.worldFromFile = Transform::translate({1, 2, 3}) * Transform::scale(Vec3f(2.0f));
    options.creaseDegrees = 0;  // the file has no normals and none are generated
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

// Float face indices (a list of double or float) are range-checked as floats before any
// integer conversion: 1e300, -1 and NaN are refused and quoted as the file gives them, never as
// an integer cast would make them (-9223372036854775808). Whole floats in range are taken.
TEST(MeshFile, PlyFloatFaceIndicesAreCheckedBeforeConversion) {
  TempDir dir;
  const std::string header =
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar double vertex_indices\nend_header\n";
  const auto binary = [&](double index) {
    Bytes body;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) body.f32(v);
    body.put(uint8_t(3)).put(0.0).put(1.0).put(index);
    return "ply\nformat binary_little_endian 1.0\n" + header + body.data;
  };
  const auto ascii = [&](const std::string& index) {
    return "ply\nformat ascii 1.0\n" + header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 " + index + "\n";
  };
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {binary(1e300), "face 0: vertex index 1e+300 is out of range (3 vertices)"},
      {binary(-1e300), "face 0: vertex index -1e+300 is out of range"},
      {binary(std::numeric_limits<double>::quiet_NaN()),
       "face 0: vertex index nan is out of range"},
      {binary(std::numeric_limits<double>::infinity()), "face 0: vertex index inf is out of range"},
      {binary(1.5), "face 0: vertex index 1.5 is not an integer"},
      {binary(3), "face 0: vertex index 3 is out of range (3 vertices)"},
      {ascii("1e300"), "face 0: vertex index 1e+300 is out of range (3 vertices)"},
      {ascii("-0.5"), "face 0: vertex index -0.5 is out of range"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.expected);
    writeFile(dir.file("f.ply"), c.text);
    expectInputError(dir.file("f.ply"), c.expected);
    Scene scene;
    try {
      loadMeshFile(dir.file("f.ply"), {}, scene);
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find("-9223372036854775808"), std::string::npos);
    }
  }
  writeFile(dir.file("ok.ply"), binary(2.0));
  EXPECT_EQ(load(dir.file("ok.ply")).triangleCount(), 1u);
  writeFile(dir.file("ok.ply"), ascii("2.0"));
  EXPECT_EQ(load(dir.file("ok.ply")).triangleCount(), 1u);
}

}  // namespace
}  // namespace parallax
