// The assimp reader (importer/mesh_assimp.cpp, docs/import.md): the formats only it reads, against
// the counts and bounds `assimp info` reports, and against our own readers on the real models
// (triangle counts, bounds, normals, textures).
#include <map>
#include <set>

#include "parallax/importer/mesh_test_support.h"

namespace parallax {
namespace {

using namespace meshtest;

// Faceted (crease 0): the readers' own normals compare, none generated.
MeshLoadOptions faceted() {
  MeshLoadOptions options;
  options.creaseDegrees = 0;
  return options;
}

// ---- assimp formats ----------------------------------------------------------------------

TEST(MeshFile, IsMeshFileKnowsAssimpFormats) {
  for (const char* name : {"a.fbx", "a.DAE", "a.3ds", "a.blend", "a.x", "a.off", "a.lwo", "a.ase",
                           "a.ms3d", "a.dxf", "a.ifc", "a.3mf"})
    EXPECT_TRUE(isMeshFile(name)) << name;
  EXPECT_FALSE(isMeshFile("a.json"));
  EXPECT_FALSE(isMeshFile("a.png"));
  EXPECT_FALSE(isMeshFile("a.txt"));
}

TEST_F(RealModels, AssimpFormats) {
  // Triangle counts and bounds from `assimp info FILE -ptv` (the assimp command line tool
  // of assimp-utils, which pre-transforms the vertices through the node hierarchy), and the
  // up axis the format implies.
  struct Case {
    const char* file;
    size_t triangles;
    Vec3f lo, hi;
    const char* up;
  };
  const Case cases[] = {
      {"assimp/FBX/box.fbx",
       12,
       {-0.226096f, -0.161864f, -0.064646f},
       {0.284462f, 0.244348f, 0.464660f},
       "y"},
      {"assimp/Collada/duck.dae",
       4212,
       {-0.692985f, 0.099294f, -0.613282f},
       {0.961799f, 1.639700f, 0.539252f},
       "y"},
      // Blender is Z-up and assimp leaves it so: the box's corners are all +-1 either way.
      {"assimp/BLEND/box.blend", 12, {-1, -1, -1}, {1, 1, 1}, "z"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const Scene scene = load(model(c.file));
    EXPECT_EQ(scene.triangleCount(), c.triangles);
    expectBounds(scene, c.lo, c.hi, 2e-6f * (1 + length(c.hi - c.lo)));
    ASSERT_EQ(scene.imports.size(), 1u);
    EXPECT_EQ(scene.imports[0].reader, "assimp");
    EXPECT_EQ(scene.imports[0].up, c.up);
  }
}

TEST_F(RealModels, AssimpReadsTexturesAndTheirMissingFiles) {
  // duck.dae names ./duckCM.tga beside it; spider.fbx names textures by absolute Windows
  // paths of the machine that wrote it, which are nowhere here: warnings, not errors.
  const Scene duck = load(model("assimp/Collada/duck.dae"));
  ASSERT_EQ(duck.materials.size(), 1u);
  ASSERT_GE(duck.materials[0].diffuseTexture, 0);
  EXPECT_EQ(duck.images.size(), 1u);
  EXPECT_FALSE(duck.meshes[0].uvs.empty());
  // An FBX with its texture embedded (a PNG inside the file, as "*0" or its file name).
  const Scene boxed = load(model("assimp/FBX/embedded_ascii/box_embedded_texture_fragmented.fbx"));
  ASSERT_EQ(boxed.materials.size(), 1u);
  ASSERT_GE(boxed.materials[0].diffuseTexture, 0);
  ASSERT_EQ(boxed.images.size(), 1u);
  EXPECT_GT(boxed.images[0].width(), 1);
  const Scene spider = load(model("assimp/FBX/spider.fbx"));
  EXPECT_EQ(spider.triangleCount(), 1312u);
  size_t missing = 0;
  for (const std::string& w : spider.warnings) missing += w.find("file not found") != w.npos;
  EXPECT_GT(missing, 0u);
}

// What an FBX or DAE import drops is said in a note, as glTF's is: the cameras and lights
// counted in the file's own text (its <camera> and <light> elements), not by assimp.
TEST_F(RealModels, AssimpSaysWhatItDrops) {
  const std::string path = model("assimp/Collada/COLLADA.dae");
  std::ifstream file(path);
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const auto occurrences = [&text](const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  // <camera id=...> and <light id=...> (the <instance_camera> and <instance_light> that place
  // them, and <camera>'s own <optics>, are not counted).
  const size_t cameras = occurrences("<camera id="), lights = occurrences("<light id=");
  ASSERT_GT(cameras, 0u);
  ASSERT_GT(lights, 0u);
  const Scene scene = load(path);
  ASSERT_EQ(scene.notes.size(), 1u);
  const std::string& note = scene.notes[0];
  EXPECT_NE(note.find("DAE (assimp): took " + std::to_string(scene.meshes.size()) + " mesh part"),
            std::string::npos)
      << note;
  EXPECT_NE(note.find(std::to_string(cameras) + " camera"), std::string::npos) << note;
  EXPECT_NE(note.find(std::to_string(lights) + " light"), std::string::npos) << note;
  EXPECT_TRUE(scene.lights.empty());
  // A file with nothing to drop says only what it took.
  const Scene plain = load(model("assimp/Collada/ConcavePolygon.dae"));
  ASSERT_EQ(plain.notes.size(), 1u);
  EXPECT_EQ(plain.notes[0].find("ignored"), std::string::npos) << plain.notes[0];
}

// ---- assimp against our readers ----------------------------------------------------------

// Looks up, for each vertex of `a`, the vertices of `b` at the same position (to within a
// cell of the grid) and expects one of them to have the same normal to within 0.1 degree.
void expectSameNormals(const Scene& a, const Scene& b) {
  const Bounds3f bounds = a.bounds();
  const float cell = 1e-4f * length(bounds.hi - bounds.lo);
  using Key = std::array<int64_t, 3>;
  auto key = [&](const Vec3f& p) {
    return Key{int64_t(std::floor(p.x / cell)), int64_t(std::floor(p.y / cell)),
               int64_t(std::floor(p.z / cell))};
  };
  std::map<Key, std::vector<std::pair<Vec3f, Vec3f>>> grid;  // position, normal
  for (const TriangleMesh& mesh : b.meshes)
    for (size_t v = 0; v < mesh.positions.size(); ++v)
      grid[key(mesh.positions[v])].push_back({mesh.positions[v], mesh.normals[v]});
  size_t compared = 0, mismatched = 0;
  for (const TriangleMesh& mesh : a.meshes)
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const Key k = key(mesh.positions[v]);
      bool found = false;
      for (int64_t dx = -1; dx <= 1; ++dx)
        for (int64_t dy = -1; dy <= 1; ++dy)
          for (int64_t dz = -1; dz <= 1; ++dz) {
            const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
            if (it == grid.end()) continue;
            for (const auto& [p, n] : it->second)
              found = found || (length(p - mesh.positions[v]) <= cell &&
                                dot(n, mesh.normals[v]) > std::cos(0.1f * kPi / 180.0f));
          }
      ++compared;
      mismatched += !found;
    }
  EXPECT_GT(compared, 0u);
  EXPECT_EQ(mismatched, 0u) << "of " << compared << " vertices";
}

TEST_F(RealModels, AssimpAgreesWithOurReaders) {
  // Both paths through loadMeshFile (same validation, degenerate dropping and axes); crease
  // 0 so that only normals the file has are compared.
  struct Case {
    const char* file;
    bool fileNormals;  // the file has vertex normals
    bool texture;
  };
  const Case cases[] = {
      {"bunny.obj", false, false},
      {"cornell_box.obj", false, false},
      {"assimp/STL/Spider_ascii.stl", false, false},
      {"assimp/STL/Spider_binary.stl", false, false},
      {"assimp/PLY/cube.ply", false, false},
      {"assimp/PLY/cube_binary.ply", false, false},
      {"assimp/PLY/Wuson.ply", true, false},
      {"assimp/glTF2/BoxTextured-glTF/BoxTextured.gltf", true, true},
      {"assimp/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", true, false},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    MeshLoadOptions ours = faceted(), theirs = faceted();
    theirs.forceAssimp = true;
    const Scene a = load(model(c.file), ours), b = load(model(c.file), theirs);
    ASSERT_EQ(b.imports.size(), 1u);
    EXPECT_EQ(b.imports[0].reader, "assimp");
    EXPECT_NE(a.imports[0].reader, "assimp");
    EXPECT_EQ(a.triangleCount(), b.triangleCount());
    const Bounds3f ba = a.bounds(), bb = b.bounds();
    const float tolerance = 1e-6f * (1 + length(ba.hi - ba.lo));
    expectNear(ba.lo, bb.lo, tolerance);
    expectNear(ba.hi, bb.hi, tolerance);
    auto textured = [](const Scene& s) {
      return std::any_of(s.materials.begin(), s.materials.end(),
                         [](const Material& m) { return m.diffuseTexture >= 0; });
    };
    EXPECT_EQ(textured(a), c.texture);
    EXPECT_EQ(textured(b), c.texture);
    EXPECT_EQ(a.imports[0].normals, c.fileNormals ? "file" : "faceted");
    if (c.fileNormals) {
      expectSameNormals(a, b);
      expectSameNormals(b, a);
    }
  }
}

}  // namespace
}  // namespace parallax
