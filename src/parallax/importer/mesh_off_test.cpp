// OFF (importer/mesh_off.cpp): a cube against the same cube in OBJ, the header's spellings, vertex
// and face colours against the sRGB formula and the PLY reader, normals, texture coordinates,
// the real models against assimp, and every refusal naming its line.
#include <map>
#include <tuple>

#include "parallax/importer/mesh_test_support.h"

namespace parallax {
namespace {

using namespace meshtest;

// IEC 61966-2-1, written out here rather than taken from the library under test.
double srgbToLinearReference(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// Every triangle of the scene, each turned to start at its smallest corner (keeping its
// winding), sorted: two readers agree if these agree, whatever order they emit in.
std::vector<std::array<Vec3f, 3>> triangleSet(const Scene& scene) {
  // Keys on a 1e-5 grid: two parsers of the same decimal text may differ in the last bit.
  const auto key = [](const Vec3f& p) {
    return std::array<int64_t, 3>{std::llround(p.x * 1e5), std::llround(p.y * 1e5),
                                  std::llround(p.z * 1e5)};
  };
  std::vector<std::array<Vec3f, 3>> all;
  for (const TriangleMesh& mesh : scene.meshes)
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      std::array<Vec3f, 3> c = triangle(mesh, t);
      size_t first = 0;
      for (size_t k = 1; k < 3; ++k)
        if (key(c[k]) < key(c[first])) first = k;
      std::rotate(c.begin(), c.begin() + std::ptrdiff_t(first), c.end());
      all.push_back(c);
    }
  std::sort(all.begin(), all.end(), [&](const auto& a, const auto& b) {
    return std::make_tuple(key(a[0]), key(a[1]), key(a[2])) <
           std::make_tuple(key(b[0]), key(b[1]), key(b[2]));
  });
  return all;
}

void expectSameTriangles(const Scene& a, const Scene& b) {
  const auto ta = triangleSet(a), tb = triangleSet(b);
  ASSERT_EQ(ta.size(), tb.size());
  ASSERT_GT(ta.size(), 0u);
  size_t differing = 0;
  for (size_t t = 0; t < ta.size(); ++t)
    for (size_t k = 0; k < 3; ++k) differing += length(ta[t][k] - tb[t][k]) > 1e-5f;
  EXPECT_EQ(differing, 0u) << "of " << ta.size() << " triangles";
}

const char* const kCubeVertices =
    "-0.5 -0.5 0.5\n0.5 -0.5 0.5\n-0.5 0.5 0.5\n0.5 0.5 0.5\n"
    "-0.5 0.5 -0.5\n0.5 0.5 -0.5\n-0.5 -0.5 -0.5\n0.5 -0.5 -0.5\n";
// The faces of the cube, 0-based, each a quad.
const int kCubeFaces[6][4] = {{0, 1, 3, 2}, {2, 3, 5, 4}, {4, 5, 7, 6},
                              {6, 7, 1, 0}, {1, 7, 5, 3}, {6, 0, 2, 4}};

TEST(OffFile, CubeEqualsTheSameCubeInObj) {
  TempDir dir;
  std::string off = "# a cube\nOFF\n\n8 6 12   # vertices faces edges\n";
  off += kCubeVertices;
  std::string obj;
  for (const char* p = kCubeVertices; *p;) {
    const char* end = std::strchr(p, '\n');
    obj += "v " + std::string(p, end) + "\n";
    p = end + 1;
  }
  for (const auto& f : kCubeFaces) {
    off += "4";
    obj += "f";
    for (int i : f) {
      off += ' ';
      off += std::to_string(i);
      obj += ' ';
      obj += std::to_string(i + 1);
    }
    off += "\n";
    obj += "\n";
  }
  writeFile(dir.file("cube.off"), off);
  writeFile(dir.file("cube.obj"), obj);
  const Scene a = load(dir.file("cube.off")), b = load(dir.file("cube.obj"));
  ASSERT_EQ(a.meshes.size(), 1u);
  ASSERT_EQ(b.meshes.size(), 1u);
  EXPECT_EQ(a.triangleCount(), 12u);
  // The same triangles in the same order: both split each quad by triangulatePolygon.
  std::vector<std::array<Vec3f, 3>> expected;
  for (size_t t = 0; t < b.meshes[0].triangleCount(); ++t)
    expected.push_back(triangle(b.meshes[0], t));
  expectTriangles(a.meshes[0], expected);
  ASSERT_EQ(a.imports.size(), 1u);
  EXPECT_EQ(a.imports[0].reader, "parallax-off");
  EXPECT_EQ(a.imports[0].up, "y");
  EXPECT_TRUE(a.warnings.empty());
}

TEST(OffFile, HeaderSpellings) {
  // The keyword and the counts on one line, ModelNet's glued count, no keyword, nOFF with its
  // dimension, comments, blank lines and CRLF: all the same triangle.
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const std::string spellings[] = {
      "OFF\n3 1 0\n" + body,
      "OFF 3 1 0\n" + body,
      "OFF3 1 0\n" + body,
      "3 1 0\n" + body,
      "nOFF 3\n3 1 0\n" + body,
      "nOFF\n3 3 1\n" + body,
      "OFF\n3 1\n" + body,
      "# comment\n\nOFF # keyword\n# counts next\n3 1 0\n\n0 0 0\n1 0 0 # x\n0 1 0\n\n3 0 1 2",
      "OFF\r\n3 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n",
  };
  TempDir dir;
  for (const std::string& text : spellings) {
    SCOPED_TRACE(text);
    writeFile(dir.file("t.off"), text);
    const Scene scene = load(dir.file("t.off"));
    ASSERT_EQ(scene.meshes.size(), 1u);
    expectTriangles(scene.meshes[0], {{Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)}});
  }
}

TEST(OffFile, VertexColoursAsCodesOrFractions) {
  TempDir dir;
  // 8-bit codes (MeshLab's COFF, with alpha) are what the PLY reader reads from uchar colours.
  writeFile(dir.file("codes.off"),
            "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 128 0 255\n0 1 0 10 20 30 255\n3 0 1 2\n");
  writeFile(dir.file("codes.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0 255 0 0\n1 0 0 0 128 0\n0 1 0 10 20 30\n3 0 1 2\n");
  const Scene off = load(dir.file("codes.off")), ply = load(dir.file("codes.ply"));
  ASSERT_EQ(off.meshes.size(), 1u);
  ASSERT_EQ(off.meshes[0].colors.size(), 3u);
  ASSERT_EQ(ply.meshes[0].colors.size(), 3u);
  for (size_t v = 0; v < 3; ++v) {
    ASSERT_EQ(off.meshes[0].positions[v], ply.meshes[0].positions[v]);
    expectNear(off.meshes[0].colors[v], ply.meshes[0].colors[v], 1e-6f);
  }
  expectNear(off.meshes[0].colors[0], {1, 0, 0}, 1e-6f);
  EXPECT_NEAR(off.meshes[0].colors[1].y, srgbToLinearReference(128 / 255.0), 1e-6);
  // Fractions (Geomview's convention, every component at most 1), without alpha.
  writeFile(dir.file("fractions.off"),
            "COFF\n3 1 0\n0 0 0 0.5 0.25 1\n1 0 0 1 1 1\n0 1 0 0 0 0.04\n3 0 1 2\n");
  const Scene f = load(dir.file("fractions.off"));
  ASSERT_EQ(f.meshes[0].colors.size(), 3u);
  const TriangleMesh& m = f.meshes[0];
  for (size_t v = 0; v < 3; ++v) {
    // The mesh keeps the file's vertex order here (each vertex first met in order).
    const Vec3f p = m.positions[v];
    const Vec3f expected = p == Vec3f(0, 0, 0)   ? Vec3f(float(srgbToLinearReference(0.5)),
                                                         float(srgbToLinearReference(0.25)), 1)
                           : p == Vec3f(1, 0, 0) ? Vec3f(1, 1, 1)
                                                 : Vec3f(0, 0, float(0.04 / 12.92));
    expectNear(m.colors[v], expected, 1e-6f);
  }
}

TEST(OffFile, FaceColoursColourTheirOwnCorners) {
  TempDir dir;
  // Two triangles sharing an edge: red and blue faces (codes), the second colour-less one
  // white. Shared vertices are split so each face keeps its colour.
  writeFile(dir.file("faces.off"),
            "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n"
            "3 0 1 2 255 0 0\n3 1 3 2 0 0 255 255\n3 0 2 3\n");
  const Scene scene = load(dir.file("faces.off"));
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.triangleCount(), 3u);
  ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
  const Vec3f expected[3] = {{1, 0, 0}, {0, 0, 1}, {1, 1, 1}};
  for (size_t t = 0; t < 3; ++t)
    for (size_t k = 0; k < 3; ++k) expectNear(mesh.colors[mesh.indices[3 * t + k]], expected[t]);
  // A colour-map index (one value) is ignored with a warning.
  writeFile(dir.file("map.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 7\n");
  const Scene mapped = load(dir.file("map.off"));
  EXPECT_TRUE(mapped.meshes.at(0).colors.empty());
  EXPECT_NE(mapped.warnings.at(0).find("colour-map indices ignored"), std::string::npos);
}

TEST(OffFile, NormalsAndTextureCoordinates) {
  TempDir dir;
  // NOFF: normals after the coordinates; STCNOFF: normals, colour, then s t.
  writeFile(dir.file("n.off"), "NOFF\n3 1 0\n0 0 0 0 0 2\n1 0 0 0 0 2\n0 1 0 0 0 2\n3 0 1 2\n");
  const Scene n = load(dir.file("n.off"));
  EXPECT_EQ(n.imports.at(0).normals, "file");
  ASSERT_EQ(n.meshes.at(0).normals.size(), 3u);
  for (const Vec3f& normal : n.meshes[0].normals) expectNear(normal, {0, 0, 1});
  writeFile(dir.file("st.off"),
            "STCNOFF\n3 1 0\n0 0 0 0 0 1 1 1 1 0 0\n1 0 0 0 0 1 1 1 1 1 0\n"
            "0 1 0 0 0 1 1 1 1 0 1\n3 0 1 2\n");
  const Scene st = load(dir.file("st.off"));
  const TriangleMesh& mesh = st.meshes.at(0);
  ASSERT_EQ(mesh.uvs.size(), 3u);
  for (size_t v = 0; v < 3; ++v) {
    EXPECT_EQ(mesh.uvs[v].x, mesh.positions[v].x);  // s, t equal x, y by construction
    EXPECT_EQ(mesh.uvs[v].y, mesh.positions[v].y);
  }
  ASSERT_EQ(mesh.colors.size(), 3u);
  expectNear(mesh.colors[0], {1, 1, 1});
}

TEST(OffFile, PolygonsAreTriangulatedAndShortFacesDropped) {
  TempDir dir;
  // A concave L-shaped hexagon (ear clipping), a 2-corner face and an empty one (dropped).
  writeFile(dir.file("l.off"),
            "OFF\n6 3 0\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n6 0 1 2 3 4 5\n2 0 1\n0\n");
  const Scene scene = load(dir.file("l.off"));
  EXPECT_EQ(scene.triangleCount(), 4u);
  EXPECT_EQ(droppedCount(scene), 2u);
  // The triangles cover the L's area, 3.
  double area = 0;
  for (size_t t = 0; t < 4; ++t)
    area += 0.5 * length(geometricNormal(triangle(scene.meshes[0], t)));
  EXPECT_NEAR(area, 3.0, 1e-6);
}

TEST(OffFile, NonsenseIsRefusedNamingTheLine) {
  TempDir dir;
  struct Case {
    const char* name;
    std::string text;
    const char* expected;
  };
  const Case cases[] = {
      // 10^9 vertices announced in 25 bytes: refused before anything is allocated (N89).
      {"billion.off", "OFF\n1000000000 0 0\n0 0 0\n",
       "line 2: the header announces 1000000000 vertices and 0 faces, more than the 6 bytes"},
      {"faces.off", "OFF\n3 100 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "100 faces, more than"},
      // A face index 7 of 3 vertices (N91).
      {"index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
       "line 6: face 0: vertex index 7 is out of range (3 vertices)"},
      {"negindex.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
       "line 6: face 0: vertex index -1 is out of range"},
      {"floatindex.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2.0\n",
       "line 6: face 0: vertex index '2.0' is not an integer"},
      {"corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000 0 1 2\n",
       "line 6: face 0: announces 1000000000 corners, the line has 3 values after it"},
      {"negcorners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n", "announces -3 corners"},
      {"extra.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 9 9\n",
       "line 6: face 0: 2 values after the corners"},
      {"vertices.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0 0\n3 0 1 2\n",
       "line 5: vertex 2: expected 3 numbers, found 4"},
      {"novertex.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n",
       "line 4: vertex 1: expected 3 numbers, found 2"},
      {"colour.off", "COFF\n3 1 0\n0 0 0 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n3 0 1 2\n",
       "line 3: vertex 0: expected 3 numbers and a colour of 3 or 4 numbers, found 5"},
      {"negcolour.off", "COFF\n3 1 0\n0 0 0 1 -1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n3 0 1 2\n",
       "line 3: vertex 0: colour -1 is negative"},
      {"nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
       "line 4: vertex 1: coordinate is NaN"},
      {"inf.off", "OFF\n3 1 0\n0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n",
       "line 4: vertex 1: coordinate is infinite"},
      {"huge.off", "OFF\n3 1 0\n0 0 0\n1 0 1e300\n0 1 0\n3 0 1 2\n",
       "line 4: vertex 1: coordinate 1e+300 is beyond the float range"},
      {"word.off", "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n",
       "line 4: vertex 1: coordinate 'zero' is not a number"},
      {"negcount.off", "OFF\n-3 1 0\n", "line 2: vertex count -3 is negative"},
      {"bigcount.off", "OFF\n3 4294967296 0\n",
       "line 2: face count 4294967296 is more than 2^31 - 1"},
      {"hugecount.off", "OFF\n99999999999999999999 1 0\n",
       "line 2: vertex count '99999999999999999999' is not an integer"},
      {"edges.off", "OFF\n3 1 -1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "edge count -1 is negative"},
      {"counts.off", "OFF\n3\n0 0 0\n", "line 2: expected the counts 'vertices faces edges'"},
      {"nocounts.off", "OFF\n# nothing else\n", "the file ends before the vertex and face counts"},
      {"truncv.off", "OFF\n3 0 0\n0.0 0.0 0.0\n1.0 0.0 0.0\n",
       "the file ends after 2 of 3 vertices (truncated?)"},
      {"truncf.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "the file ends after 1 of 2 faces (truncated?)"},
      {"binary.off", std::string("OFF BINARY\n\0\0\0\3\0\0\0\1\0\0\0\0", 23),
       "binary OFF ('OFF BINARY') is not supported"},
      {"fourd.off", "4OFF\n3 1 0\n", "4-D OFF ('4OFF') is not supported, only 3-D"},
      {"nd.off", "nOFF 4\n3 1 0\n", "a 4-D OFF is not supported, only 3-D"},
      {"keyword.off", "OFFICE\n3 1 0\n", "line 1: unknown keyword 'OFFICE'"},
      {"prefix.off", "XOFF\n3 1 0\n", "line 1: unknown keyword 'XOFF'"},
      {"text.off", "hello world\n", "line 1: no OFF keyword and no counts (not an OFF file?)"},
      {"comment.off", "# only a comment\n", "no header (not an OFF file?)"},
      {"empty.off", "", "file is empty"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    writeFile(dir.file(c.name), c.text);
    expectInputError(dir.file(c.name), c.expected);
  }
}

TEST(OffFile, LinesAfterTheLastFaceAreAWarning) {
  TempDir dir;
  writeFile(dir.file("tail.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n1 2\n3 4\n");
  const Scene scene = load(dir.file("tail.off"));
  EXPECT_EQ(scene.triangleCount(), 1u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("ignored 2 lines after the last face"), std::string::npos);
}

TEST_F(RealModels, OffModelsEqualAssimpsReading) {
  // assimp's OFF importer, an independent reader of the same files: the same triangles.
  for (const char* file : {"assimp/OFF/Cube.off", "assimp/OFF/Wuson.off"}) {
    SCOPED_TRACE(file);
    MeshLoadOptions assimp;
    assimp.forceAssimp = true;
    const Scene ours = load(model(file)), theirs = load(model(file), assimp);
    EXPECT_EQ(ours.imports.at(0).reader, "parallax-off");
    EXPECT_EQ(theirs.imports.at(0).reader, "assimp");
    expectSameTriangles(ours, theirs);
  }
}

TEST_F(RealModels, AssimpsBrokenOffFilesAreRefused) {
  // Its OutOfMemory.off announces 353535235358 vertices in 309 bytes (assimp allocates for
  // them, docs/import.md); invalid.off's second face is "2\r20": 2 corners, one value.
  expectInputError(model("assimp/invalid/OutOfMemory.off"),
                   "vertex count 353535235358 is more than 2^31 - 1");
  expectInputError(model("assimp/OFF/invalid.off"),
                   "line 7: face 1: announces 2 corners, the line has 1 value after it");
}

}  // namespace
}  // namespace parallax
