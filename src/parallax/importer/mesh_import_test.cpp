// What loadMeshFile adds to every reader (docs/import.md): the assimp reader against our own
// on the real models, generated normals with a crease angle, and the up axis.
#include <map>
#include <numbers>
#include <set>

#include "parallax/importer/mesh_test_support.h"
#include "parallax/importer/scene_file.h"

namespace parallax {
namespace {

using namespace meshtest;

constexpr float kPi = std::numbers::pi_v<float>;

// ---- Synthetic meshes without normals ---------------------------------------------------

// A UV sphere of radius r around c as OBJ text: `rings` latitude bands, `segments` longitudes,
// one vertex per pole, counter-clockwise seen from outside.
std::string sphereObj(int rings, int segments, float r = 1.0f, Vec3f c = Vec3f(0.0f)) {
  std::ostringstream obj;
  obj << "v " << c.x << " " << c.y + r << " " << c.z << "\n";  // north pole: vertex 1
  for (int i = 1; i < rings; ++i) {
    const float theta = kPi * float(i) / float(rings);
    for (int j = 0; j < segments; ++j) {
      const float phi = 2 * kPi * float(j) / float(segments);
      obj << "v " << c.x + r * std::sin(theta) * std::cos(phi) << " " << c.y + r * std::cos(theta)
          << " " << c.z - r * std::sin(theta) * std::sin(phi) << "\n";
    }
  }
  const int south = 2 + (rings - 1) * segments;
  obj << "v " << c.x << " " << c.y - r << " " << c.z << "\n";
  auto at = [&](int ring, int j) { return 2 + (ring - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) obj << "f 1 " << at(1, j) << " " << at(1, j + 1) << "\n";
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j)
      obj << "f " << at(i, j) << " " << at(i + 1, j) << " " << at(i + 1, j + 1) << " "
          << at(i, j + 1) << "\n";
  for (int j = 0; j < segments; ++j)
    obj << "f " << south << " " << at(rings - 1, j + 1) << " " << at(rings - 1, j) << "\n";
  return obj.str();
}

// The unit cube [0,1]^3 with 8 shared vertices and outward quads.
const char* const kCubeObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";

// Two unit squares sharing the edge x = 0 (along z), one in the XZ plane (normal +y), the
// other turned about that edge so that the faces' normals are `degrees` apart.
std::string hingeObj(float degrees) {
  const float a = degrees * kPi / 180.0f;
  std::ostringstream obj;
  obj << "v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\n"                // flat square
      << "v " << -std::cos(a) << " " << std::sin(a) << " 1\n"  // the turned one
      << "v " << -std::cos(a) << " " << std::sin(a) << " 0\n"
      << "f 1 2 3 4\nf 6 5 2 1\n";
  return obj.str();
}

MeshLoadOptions withCrease(float degrees) {
  MeshLoadOptions options;
  options.creaseDegrees = degrees;
  return options;
}

// The shading normal at every corner of the mesh's triangles, with the triangle's own unit
// geometric normal.
struct Corner {
  Vec3f position, normal, face;
};
std::vector<Corner> corners(const TriangleMesh& mesh) {
  std::vector<Corner> out;
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3f face = normalize(geometricNormal(triangle(mesh, t)));
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + size_t(k)];
      out.push_back({mesh.positions[v], mesh.normals[v], face});
    }
  }
  return out;
}

float degreesBetween(const Vec3f& a, const Vec3f& b) {
  return std::acos(std::clamp(dot(normalize(a), normalize(b)), -1.0f, 1.0f)) * 180.0f / kPi;
}

TEST(GeneratedNormals, SphereNormalsAreRadial) {
  TempDir dir;
  const std::string path = dir.file("sphere.obj");
  const Vec3f center(1, 2, 3);
  writeFile(path, sphereObj(24, 48, 2.0f, center));
  const Scene scene = load(path);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  // Neighbouring faces are 7.5 degrees apart (well inside 60), so the sphere is smooth: one
  // normal per vertex, and the angle-weighted sum of a vertex's faces is the radial
  // direction up to the grid's asymmetry between the bands above and below (O(h^2)).
  EXPECT_EQ(mesh.positions.size(), size_t(2 + 23 * 48));
  float worst = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    worst = std::max(worst, degreesBetween(mesh.normals[v], mesh.positions[v] - center));
  EXPECT_LT(worst, 0.5f);
  ASSERT_EQ(scene.imports.size(), 1u);
  EXPECT_EQ(scene.imports[0].normals, "generated (crease 60°)");
  EXPECT_EQ(scene.imports[0].reader, "parallax-obj");
  EXPECT_EQ(scene.imports[0].triangles, mesh.triangleCount());
}

TEST(GeneratedNormals, MirroredSphereStillPointsOutward) {
  TempDir dir;
  const std::string path = dir.file("sphere.obj");
  writeFile(path, sphereObj(12, 24));
  MeshLoadOptions options;
  options.worldFromFile = Transform::scale({-1, 2, 1});  // mirrors: the loader swaps windings
  const Scene scene = load(path, options);
  const TriangleMesh& mesh = scene.meshes[0];
  for (const Corner& c : corners(mesh)) {
    EXPECT_GT(dot(c.normal, c.position), 0.0f);
    EXPECT_GT(dot(c.face, c.position), 0.0f);  // the swap kept the faces outward too
  }
}

TEST(GeneratedNormals, CubeKeepsItsSixFaceNormals) {
  TempDir dir;
  const std::string path = dir.file("cube.obj");
  writeFile(path, kCubeObj);
  const Scene scene = load(path);
  const TriangleMesh& mesh = scene.meshes[0];
  ASSERT_EQ(mesh.triangleCount(), 12u);
  // Faces meet at 90 degrees, more than 60: every corner keeps its face's normal, so each
  // of the 8 corners of the cube is split into 3 vertices.
  EXPECT_EQ(mesh.positions.size(), 24u);
  std::set<std::array<float, 3>> distinct;
  for (const Corner& c : corners(mesh)) {
    expectNear(c.normal, c.face, 1e-6f);
    distinct.insert({c.normal.x, c.normal.y, c.normal.z});
  }
  EXPECT_EQ(distinct.size(), 6u);
  // Outward: the normal points away from the cube's centre.
  for (const Corner& c : corners(mesh)) EXPECT_GT(dot(c.normal, c.position - Vec3f(0.5f)), 0.0f);
}

TEST(GeneratedNormals, CreaseAngleDecidesEitherSideOfTheThreshold) {
  TempDir dir;
  const Vec3f flat(0, 1, 0);
  for (float dihedral : {50.0f, 70.0f}) {
    SCOPED_TRACE(dihedral);
    const std::string path = dir.file("hinge.obj");
    writeFile(path, hingeObj(dihedral));
    const Scene scene = load(path, withCrease(60.0f));
    const TriangleMesh& mesh = scene.meshes[0];
    const float a = dihedral * kPi / 180.0f;
    const Vec3f turned(std::sin(a), std::cos(a), 0);  // the second square's normal
    ASSERT_NEAR(degreesBetween(flat, turned), dihedral, 1e-3f);
    for (const Corner& c : corners(mesh)) {
      const bool onHinge = c.position.x == 0.0f;
      if (!onHinge) {
        expectNear(c.normal, c.face, 1e-6f);  // only its own square around it
      } else if (dihedral < 60.0f) {
        // Both squares are within the crease: each hinge corner has two right angles, one of
        // each square (the square's two triangles there: 90 = 45 + 45), so the weights are
        // equal and the normal is the bisector.
        expectNear(c.normal, normalize(flat + turned), 1e-5f);
      } else {
        expectNear(c.normal, c.face, 1e-6f);  // split: each square keeps its own
      }
    }
    // 4 + 4 corners; the 2 hinge vertices are shared when smooth.
    EXPECT_EQ(mesh.positions.size(), dihedral < 60.0f ? 4u + 2u : 4u + 4u);
  }
}

// A low cone (apex at height 0.1 over a unit disc) of `segments` triangles around its apex.
std::string coneObj(int segments) {
  std::ostringstream obj;
  obj << "v 0 0.1 0\n";
  for (int j = 0; j < segments; ++j) {
    const float phi = 2 * kPi * float(j) / float(segments);
    obj << "v " << std::cos(phi) << " 0 " << -std::sin(phi) << "\n";
  }
  for (int j = 0; j < segments; ++j)
    obj << "f 1 " << 2 + j << " " << 2 + (j + 1) % segments << "\n";
  return obj.str();
}

TEST(GeneratedNormals, CrowdedVerticesAreBoundedAndSaySo) {
  TempDir dir;
  // 4000 faces around the apex, all within 12 degrees of each other: smooth, and by symmetry
  // the apex normal is the axis.
  writeFile(dir.file("cone.obj"), coneObj(4000));
  const Scene smooth = load(dir.file("cone.obj"));
  EXPECT_TRUE(smooth.warnings.empty());
  for (const Corner& c : corners(smooth.meshes[0]))
    if (c.position == Vec3f(0, 0.1f, 0)) expectNear(c.normal, {0, 1, 0}, 1e-4f);
  // 5000: more than the 4096 compared pairwise; the apex keeps its faces' normals, with a
  // warning, instead of 25 million comparisons per crowded vertex.
  writeFile(dir.file("cone.obj"), coneObj(5000));
  const Scene crowded = load(dir.file("cone.obj"));
  ASSERT_EQ(crowded.warnings.size(), 1u);
  EXPECT_NE(crowded.warnings[0].find("1 vertex shared by more than 4096 triangles"),
            std::string::npos)
      << crowded.warnings[0];
  size_t apexCorners = 0;
  for (const Corner& c : corners(crowded.meshes[0]))
    if (c.position == Vec3f(0, 0.1f, 0)) expectNear(c.normal, c.face, 1e-6f), ++apexCorners;
  EXPECT_EQ(apexCorners, 5000u);
}

TEST(GeneratedNormals, CreaseZeroIsFacetedAsBefore) {
  TempDir dir;
  const std::string path = dir.file("sphere.obj");
  writeFile(path, sphereObj(8, 16));
  const Scene scene = load(path, withCrease(0.0f));
  EXPECT_TRUE(scene.meshes[0].normals.empty());
  EXPECT_EQ(scene.imports[0].normals, "faceted");
}

TEST(GeneratedNormals, FileNormalsAreKept) {
  TempDir dir;
  const std::string path = dir.file("tilted.obj");
  // One triangle in the XY plane whose file normals lean: they must come out unchanged.
  writeFile(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0.6 0 0.8\nf 1//1 2//1 3//1\n");
  const Scene scene = load(path);
  for (const Vec3f& n : scene.meshes[0].normals) expectNear(n, {0.6f, 0, 0.8f}, 1e-6f);
  EXPECT_EQ(scene.imports[0].normals, "file");
}

TEST(GeneratedNormals, StlVerticesAreWeldedByPosition) {
  // STL repeats each corner per triangle; generation matches them by position, so a sphere
  // written as STL is as smooth as the OBJ one.
  TempDir dir;
  writeFile(dir.file("s.obj"), sphereObj(12, 24));
  const Scene obj = load(dir.file("s.obj"));
  std::ostringstream stl;
  stl << "solid s\n";
  const TriangleMesh& mesh = obj.meshes[0];
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    stl << "facet normal 0 0 0\nouter loop\n";
    for (const Vec3f& p : triangle(mesh, t))
      stl << "vertex " << p.x << " " << -p.z << " " << p.y << "\n";  // Z-up, as STL is
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid s\n";
  writeFile(dir.file("s.stl"), stl.str());
  const Scene fromStl = load(dir.file("s.stl"));
  ASSERT_EQ(fromStl.meshes[0].triangleCount(), mesh.triangleCount());
  float worst = 0;
  for (const Corner& c : corners(fromStl.meshes[0]))
    worst = std::max(worst, degreesBetween(c.normal, c.position));
  EXPECT_LT(worst, 2.0f);  // radial to within the coarse grid's error, not faceted (7.5+)
}

// ---- Up axis -----------------------------------------------------------------------------

// Extent of the scene's bounds along each axis.
Vec3f extent(const Scene& scene) {
  const Bounds3f b = scene.bounds();
  return b.hi - b.lo;
}

TEST_F(RealModels, SpiderStandsUpAfterTheZUpTurn) {
  // The Spider's bounds in its own axes are (-3.114895 -4 -1.649329) .. (3.114895 4 1.649329)
  // (assimp, mesh_test_support.h): read as Y-up its 8 units of leg span stand vertically.
  MeshLoadOptions asY;
  asY.up = UpAxis::Y;
  const Scene lying = load(model("assimp/STL/Spider_ascii.stl"), asY);
  EXPECT_EQ(lying.imports[0].up, "y");
  const Vec3f before = extent(lying);
  EXPECT_GT(before.y, before.x);
  EXPECT_GT(before.y, before.z);
  // Auto (Z for STL): -90 degrees about X, (x, y, z) -> (x, z, -y), so the legs lie in XZ
  // and its 3.3 units of height are now Y, the smallest extent.
  const Scene standing = load(model("assimp/STL/Spider_ascii.stl"));
  EXPECT_EQ(standing.imports[0].up, "z");
  expectBounds(standing, {-3.114895f, -1.649329f, -4}, {3.114895f, 1.649329f, 4}, 1e-5f);
  const Vec3f after = extent(standing);
  EXPECT_LT(after.y, after.x);
  EXPECT_LT(after.y, after.z);
}

TEST(UpAxis, ExplicitChoiceOverridesTheFormat) {
  TempDir dir;
  const std::string path = dir.file("post.obj");
  // A thin post along +Z.
  writeFile(path, "v 0 0 0\nv 0.1 0 0\nv 0 0 5\nf 1 2 3\n");
  const Scene autoUp = load(path);  // OBJ: Y-up, left alone
  expectBounds(autoUp, {0, 0, 0}, {0.1f, 0, 5}, 0);
  MeshLoadOptions z;
  z.up = UpAxis::Z;
  z.worldFromFile = Transform::translate({0, 0, 1});  // after the turn, in world space
  const Scene turned = load(path, z);
  expectBounds(turned, {0, 0, 1}, {0.1f, 5, 1}, 0);
  EXPECT_EQ(turned.imports[0].up, "z");
  // The turn is a rotation: winding and hence the face's side are kept ((0,0,1) -> (0,1,0)).
  const Vec3f n = geometricNormal(triangle(turned.meshes[0], 0));
  const Vec3f n0 = geometricNormal(triangle(autoUp.meshes[0], 0));
  expectNear(normalize(n), normalize(Vec3f(n0.x, n0.z, -n0.y)), 1e-6f);
}

TEST(UpAxis, Names) {
  UpAxis up = UpAxis::Y;
  EXPECT_TRUE(parseUpAxis("auto", up));
  EXPECT_EQ(up, UpAxis::Auto);
  EXPECT_TRUE(parseUpAxis("z", up));
  EXPECT_EQ(up, UpAxis::Z);
  EXPECT_FALSE(parseUpAxis("Z-up", up));
  EXPECT_EQ(up, UpAxis::Z);
}

TEST_F(RealModels, FbxDeclaresItsUpAxis) {
  // assimp's box.FBX (embedded_ascii) says UpAxis 2 (+Z): auto turns it Y-up, and the box,
  // 1.2 units tall from its base at z = 0, then stands on y = 0.
  const std::string zUp = model("assimp/FBX/embedded_ascii/box.FBX");
  const Scene standing = load(zUp);
  EXPECT_EQ(standing.imports[0].up, "z");
  expectBounds(standing, {-0.6f, 0, -0.6f}, {0.6f, 1.2f, 0.6f}, 1e-6f);
  MeshLoadOptions asY;
  asY.up = UpAxis::Y;
  const Scene asFile = load(zUp, asY);
  expectBounds(asFile, {-0.6f, -0.6f, 0}, {0.6f, 0.6f, 1.2f}, 1e-6f);

  // The same ASCII file twice, differing only in the UpAxis it declares: the metadata alone
  // decides, and Z gives the rotation of the Y file's bounds, (x, y, z) -> (x, z, -y).
  TempDir dir;
  const std::string text =
      readFile(model("assimp/FBX/embedded_ascii/box_embedded_texture_fragmented.fbx"));
  const std::string yLine = R"(P: "UpAxis", "int", "Integer", "",1)";
  const size_t at = text.find(yLine);
  ASSERT_NE(at, std::string::npos);
  std::string zText = text;
  zText[at + yLine.size() - 1] = '2';
  writeFile(dir.file("y.fbx"), text);
  writeFile(dir.file("z.fbx"), zText);
  const Scene y = load(dir.file("y.fbx")), z = load(dir.file("z.fbx"));
  EXPECT_EQ(y.imports[0].up, "y");
  EXPECT_EQ(z.imports[0].up, "z");
  const Bounds3f by = y.bounds(), bz = z.bounds();
  expectNear(bz.lo, {by.lo.x, by.lo.z, -by.hi.y}, 1e-6f);
  expectNear(bz.hi, {by.hi.x, by.hi.z, -by.lo.y}, 1e-6f);
}

// ---- Scene files -------------------------------------------------------------------------

TEST_F(RealModels, SceneFileUpAndCreaseKeys) {
  TempDir dir;
  const std::string scene = dir.file("scene.json");
  writeFile(scene, R"({"objects": [
      {"shape": "mesh", "file": ")" +
                       model("assimp/STL/Spider_ascii.stl") +
                       R"(", "up": "y", "crease": 0},
      {"shape": "mesh", "file": ")" +
                       model("assimp/STL/Spider_binary.stl") + R"("}]})");
  const Scene s = loadScene(scene);
  ASSERT_EQ(s.imports.size(), 2u);
  EXPECT_EQ(s.imports[0].up, "y");
  EXPECT_EQ(s.imports[0].normals, "faceted");
  EXPECT_EQ(s.imports[1].up, "z");
  EXPECT_EQ(s.imports[1].normals, "generated (crease 60°)");
  // The caller's defaults apply where the object says nothing.
  SceneLoadOptions defaults;
  defaults.import.up = UpAxis::Y;
  defaults.import.creaseDegrees = 30;
  const Scene d = loadScene(scene, defaults);
  EXPECT_EQ(d.imports[1].up, "y");
  EXPECT_EQ(d.imports[1].normals, "generated (crease 30°)");

  for (const auto& [key, needle] :
       std::vector<std::pair<std::string, std::string>>{{R"("up": "x")", "/objects/0/up"},
                                                        {R"("crease": 181)", "/objects/0/crease"},
                                                        {R"("crease": -1)", "/objects/0/crease"}}) {
    writeFile(scene, R"({"objects": [{"shape": "mesh", "file": ")" +
                         model("assimp/STL/Spider_ascii.stl") + "\", " + key + "}]}");
    try {
      loadScene(scene);
      ADD_FAILURE() << key << ": no InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
}

TEST_F(RealModels, SimulateReloadsWithTheRecordedImportOptions) {
  // simulate --reference reloads the scene a render drew (loadSceneAsRendered): the import
  // options in its render.json make the meshes the same.
  TempDir dir;
  const std::string spider = model("assimp/STL/Spider_ascii.stl");
  writeFile(dir.file("render.json"), R"({"import_options": {"up": "y", "crease": 0}})");
  const Scene recorded = loadSceneAsRendered(spider, dir.file(""));
  EXPECT_EQ(recorded.imports[0].up, "y");
  EXPECT_EQ(recorded.imports[0].normals, "faceted");
  writeFile(dir.file("render.json"), "{}");  // a record from before: the defaults
  const Scene old = loadSceneAsRendered(spider, dir.file(""));
  EXPECT_EQ(old.imports[0].up, "z");
  EXPECT_EQ(old.imports[0].normals, "generated (crease 60°)");
  writeFile(dir.file("render.json"), R"({"import_options": {"up": "sideways", "crease": 0}})");
  try {
    loadSceneAsRendered(spider, dir.file(""));
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/import_options/up"), std::string::npos) << e.what();
  }
}

// ---- The bunny ---------------------------------------------------------------------------

TEST_F(RealModels, BunnyNormalsPointOutward) {
  const Scene scene = load(model("bunny.obj"));
  ASSERT_EQ(scene.imports[0].normals, "generated (crease 60°)");
  Vec3f centroid(0.0f);
  size_t count = 0;
  for (const TriangleMesh& mesh : scene.meshes)
    for (const Vec3f& p : mesh.positions) centroid += p, ++count;
  centroid = centroid / float(count);
  size_t outward = 0;
  for (const TriangleMesh& mesh : scene.meshes) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v)
      outward += dot(mesh.normals[v], mesh.positions[v] - centroid) > 0;
  }
  // Not all: the bunny is not convex (ears, the hollows under its chin and its feet).
  EXPECT_GT(double(outward), 0.85 * double(count)) << outward << " of " << count;
}

}  // namespace
}  // namespace parallax
