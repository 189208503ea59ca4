#include "parallax/importer/scene_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "parallax/core/error.h"
#include "parallax/io/image_file.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

void expectNear(const Vec3f& a, const Vec3f& b, float tolerance = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

class SceneFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("parallax_scene_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  Scene load(const std::string& json) const { return loadScene(write("scene.json", json)); }

  // Loads `json`, expects an InputError at `pointer` whose message contains `needle`.
  void expectError(const std::string& json, const std::string& pointer,
                   const std::string& needle) const {
    const std::string file = write("scene.json", json);
    try {
      loadScene(file);
      ADD_FAILURE() << "no error for " << json;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file) << e.what();
      EXPECT_EQ(e.path(), pointer) << e.what();
      EXPECT_EQ(
          std::string(e.what()).rfind(file + ": " + (pointer.empty() ? "" : pointer + ": "), 0), 0u)
          << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }

  // A one-triangle OBJ beside the scene.
  void writeTriangleObj(const std::string& name) const {
    write(name, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  }

  fs::path dir_;
};

// Checks that each triangle's winding agrees with its vertex normals and that both point away
// from `inside` (a point within the closed mesh).
void expectOutwardWinding(const TriangleMesh& mesh, const Vec3f& inside) {
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Vec3f a = mesh.positions[mesh.indices[3 * t]];
    const Vec3f b = mesh.positions[mesh.indices[3 * t + 1]];
    const Vec3f c = mesh.positions[mesh.indices[3 * t + 2]];
    const Vec3f geometric = cross(b - a, c - a);
    const Vec3f outward = (a + b + c) / 3.0f - inside;
    EXPECT_GT(dot(geometric, outward), 0) << "triangle " << t;
    EXPECT_GT(dot(geometric, mesh.normals[mesh.indices[3 * t]]), 0) << "triangle " << t;
  }
}

TEST_F(SceneFileTest, ReadsTopLevelSettingsAndSpheres) {
  const Scene scene = load(R"({
    "version": 1,
    // comments are allowed
    "materials": {"red": {"color": [0.8, 0.1, 0.1], "mirror": 0.25}},
    "objects": [{"name": "ball", "shape": "sphere", "center": [1, 2, 3], "radius": 0.5,
                 "material": "red"}],
    "lights": [{"type": "point", "position": [0, 5, 0], "intensity": [10, 20, 30]},
               {"type": "directional", "direction": [0, -2, 0], "irradiance": 2}],
    "ambient": 0.1, "background": [0.1, 0.2, 0.3], "max_depth": 7,
    "camera": {"eye": [0, 0, 10], "look_at": [0, 0, 0], "up": [0, 2, 0], "fov": 30},
    "display": {"center": [0, 1, 0], "normal": [0, 0, 2], "up": [0, 1, 0.5], "width": 3}
  })");
  ASSERT_EQ(scene.spheres.size(), 1u);
  EXPECT_EQ(scene.spheres[0].name, "ball");
  EXPECT_EQ(scene.spheres[0].center, Vec3f(1, 2, 3));
  EXPECT_EQ(scene.spheres[0].radius, 0.5f);
  const Material& red = scene.materials[scene.spheres[0].material];
  EXPECT_EQ(red.name, "red");
  EXPECT_EQ(red.diffuse, Vec3f(0.8f, 0.1f, 0.1f));
  EXPECT_EQ(red.mirror, Vec3f(0.25f));
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].kind, Light::Kind::Point);
  EXPECT_EQ(scene.lights[0].position, Vec3f(0, 5, 0));
  EXPECT_EQ(scene.lights[0].intensity, Vec3f(10, 20, 30));
  EXPECT_EQ(scene.lights[1].kind, Light::Kind::Directional);
  EXPECT_EQ(scene.lights[1].direction, Vec3f(0, -1, 0));
  EXPECT_EQ(scene.lights[1].intensity, Vec3f(2.0f));
  EXPECT_EQ(scene.ambient, Vec3f(0.1f));
  EXPECT_EQ(scene.background, Vec3f(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(scene.maxDepth, 7);
  ASSERT_TRUE(scene.camera);
  EXPECT_EQ(scene.camera->eye, Vec3f(0, 0, 10));
  EXPECT_EQ(scene.camera->up, Vec3f(0, 1, 0));
  EXPECT_EQ(scene.camera->fovDegrees, 30.0f);
  EXPECT_EQ(scene.display.center, Vec3f(0, 1, 0));
  EXPECT_EQ(scene.display.normal, Vec3f(0, 0, 1));
  EXPECT_EQ(scene.display.up, Vec3f(0, 1, 0));  // made perpendicular to the normal
  EXPECT_EQ(scene.display.width, 3.0f);
  EXPECT_FALSE(scene.display.fit);  // a given width is used as it is
  EXPECT_TRUE(scene.warnings.empty());
}

TEST_F(SceneFileTest, DefaultsFrameTheSceneAndPlaceTheDisplayAtItsBounds) {
  const Scene scene = load(R"({"objects": [
    {"shape": "sphere", "center": [1, 2, 3], "radius": 0.5},
    {"shape": "box", "min": [-2, 0, 0], "max": [0, 1, 1]}]})");
  // Bounds: x from -2 to 1.5, y from 0 to 2.5, z from 0 to 3.5.
  expectNear(scene.display.center, {-0.25f, 1.25f, 1.75f});
  EXPECT_EQ(scene.display.normal, Vec3f(0, 0, 1));
  EXPECT_EQ(scene.display.up, Vec3f(0, 1, 0));
  EXPECT_FLOAT_EQ(scene.display.width, 3.5f);
  // Without a width the display is fitted to each display's window around these bounds.
  ASSERT_TRUE(scene.display.fit);
  expectNear(scene.display.fit->lo, {-2, 0, 0});
  expectNear(scene.display.fit->hi, {1.5f, 2.5f, 3.5f});
  const CameraSpec framed = frameScene(scene);
  ASSERT_TRUE(scene.camera);
  EXPECT_EQ(scene.camera->eye, framed.eye);
  EXPECT_EQ(scene.camera->lookAt, framed.lookAt);
  EXPECT_EQ(scene.camera->fovDegrees, framed.fovDegrees);
  // Both objects share one default grey material.
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].diffuse, Vec3f(0.8f));
  EXPECT_EQ(scene.spheres[0].name, "sphere 0");
  EXPECT_EQ(scene.meshes[0].name, "box 1");
}

TEST_F(SceneFileTest, MaterialsTexturesAndImages) {
  Image pattern(2, 1);
  pattern.at(0, 0) = Vec3f(srgb8ToLinear(200));
  pattern.at(1, 0) = Vec3f(srgb8ToLinear(20));
  writeImage((dir_ / "tex" / "pattern.png").string(), pattern);
  const Scene scene = load(R"({
    "textures": {"wood": {"type": "image", "file": "tex/pattern.png"},
                 "tiles": {"type": "checker", "color1": 0.9, "color2": [0.1, 0, 0], "size": 0.25}},
    "materials": {
      "floor": {"texture": "tiles"},
      "panel": {"diffuse": [0.5, 0.5, 0.5], "texture": "wood"},
      "copy": {"texture": {"type": "image", "file": "./tex/../tex/pattern.png"}},
      "lamp": {"emission": [1, 2, 3], "emission_strength": 2},
      "glow": {"emission_strength": 5}
    },
    "objects": [{"shape": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0],
                 "material": {"color": 0.3, "mirror": [0.1, 0.2, 0.3]}}]
  })");
  ASSERT_EQ(scene.textures.size(), 3u);
  EXPECT_EQ(scene.textures[0].kind, Texture::Kind::Image);
  EXPECT_EQ(scene.textures[1].kind, Texture::Kind::Checker);
  EXPECT_EQ(scene.textures[1].color, Vec3f(0.9f));
  EXPECT_EQ(scene.textures[1].color2, Vec3f(0.1f, 0, 0));
  EXPECT_EQ(scene.textures[1].checkerSize, 0.25f);
  // Both image textures name the same file, which is loaded once.
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.textures[2].image, 0);
  EXPECT_EQ(scene.images[0].at(0, 0), Vec3f(srgb8ToLinear(200)));
  ASSERT_EQ(scene.materials.size(), 6u);
  EXPECT_EQ(scene.materials[0].diffuseTexture, 1);
  EXPECT_EQ(scene.materials[0].diffuse, Vec3f(1.0f));  // white under a texture
  EXPECT_EQ(scene.materials[1].diffuseTexture, 0);
  EXPECT_EQ(scene.materials[1].diffuse, Vec3f(0.5f));
  EXPECT_EQ(scene.materials[3].emission, Vec3f(2, 4, 6));
  EXPECT_EQ(scene.materials[4].emission, Vec3f(5.0f));
  const Material& inlined = scene.materials[scene.meshes[0].material];
  EXPECT_EQ(inlined.name, "quad 0");
  EXPECT_EQ(inlined.diffuse, Vec3f(0.3f));
  EXPECT_EQ(inlined.mirror, Vec3f(0.1f, 0.2f, 0.3f));
}

TEST_F(SceneFileTest, TransformStepsApplyInListOrder) {
  // Unit box, scaled by 2, turned 90 degrees about +z ((x, y, z) -> (-y, x, z)), moved +1 in x:
  // corner (x, y, z) ends at (1 - 2y, 2x, 2z).
  const Scene scene = load(R"({"objects": [{"shape": "box", "min": [0, 0, 0], "max": [1, 1, 1],
    "transform": [{"scale": 2}, {"rotate": {"angle": 90, "axis": [0, 0, 1]}},
                  {"translate": [1, 0, 0]}]}]})");
  const TriangleMesh& box = scene.meshes.at(0);
  for (float x : {0.0f, 1.0f})
    for (float y : {0.0f, 1.0f})
      for (float z : {0.0f, 1.0f}) {
        const Vec3f expected{1 - 2 * y, 2 * x, 2 * z};
        const bool found =
            std::any_of(box.positions.begin(), box.positions.end(),
                        [&](const Vec3f& p) { return length(p - expected) < 1e-5f; });
        EXPECT_TRUE(found) << expected.x << " " << expected.y << " " << expected.z;
      }
  for (const Vec3f& p : box.positions) {
    EXPECT_GE(p.x, -1 - 1e-5f);
    EXPECT_LE(p.x, 1 + 1e-5f);
    EXPECT_GE(p.y, -1e-5f);
    EXPECT_LE(p.y, 2 + 1e-5f);
  }
  expectOutwardWinding(box, {0, 1, 1});
}

TEST_F(SceneFileTest, TransformOrderMattersAndMatrixFormsAgree) {
  const Scene scene = load(R"({"objects": [
    {"shape": "sphere", "radius": 1, "transform": [{"translate": [1, 0, 0]}, {"scale": 2}]},
    {"shape": "sphere", "radius": 1, "transform": [{"scale": 2}, {"translate": [1, 0, 0]}]},
    {"shape": "sphere", "radius": 1, "center": [1, 1, 1],
     "transform": {"matrix": [0, -3, 0, 5,  3, 0, 0, 6,  0, 0, 3, 7,  0, 0, 0, 1]}},
    {"shape": "sphere", "radius": 1, "center": [1, 1, 1],
     "transform": {"matrix": [[0, -3, 0, 5], [3, 0, 0, 6], [0, 0, 3, 7], [0, 0, 0, 1]]}},
    {"shape": "sphere", "radius": 1, "transform": [{"scale": [-2, 2, 2]}]}]})");
  ASSERT_EQ(scene.spheres.size(), 5u);
  expectNear(scene.spheres[0].center, {2, 0, 0});
  expectNear(scene.spheres[1].center, {1, 0, 0});
  EXPECT_FLOAT_EQ(scene.spheres[0].radius, 2);
  // Row-major with the translation in the last column: (1,1,1) -> (5-3, 6+3, 7+3).
  expectNear(scene.spheres[2].center, {2, 9, 10});
  EXPECT_FLOAT_EQ(scene.spheres[2].radius, 3);
  expectNear(scene.spheres[3].center, scene.spheres[2].center);
  EXPECT_FLOAT_EQ(scene.spheres[4].radius, 2);  // a mirrored sphere is still a sphere
}

TEST_F(SceneFileTest, MirroringTransformKeepsBoxesOutwardFacing) {
  const Scene scene = load(R"({"objects": [{"shape": "box", "size": [1, 2, 3], "center": [0, 0, 0],
    "transform": [{"scale": [-1, 1, 1]}, {"translate": [5, 0, 0]}]}]})");
  expectOutwardWinding(scene.meshes.at(0), {5, 0, 0});
  EXPECT_FLOAT_EQ(scene.bounds().lo.z, -1.5f);
}

TEST_F(SceneFileTest, QuadsAndPlanes) {
  const Scene scene = load(R"({"objects": [
    {"shape": "quad", "corner": [1, 2, 3], "edge_u": [2, 0, 0], "edge_v": [0, 0, -1]},
    {"shape": "plane", "center": [0, -1, 0], "normal": [0, 1, 0], "size": [4, 2]},
    {"shape": "plane", "center": [0, 0, -5], "normal": [0, 0, 1], "up": [1, 1, 0], "size": 2}]})");
  ASSERT_EQ(scene.meshes.size(), 3u);
  const TriangleMesh& quad = scene.meshes[0];
  EXPECT_EQ(quad.positions[2], Vec3f(3, 2, 2));
  EXPECT_EQ(quad.normals[0], Vec3f(0, 1, 0));  // cross(+x, -z) = +y
  // A floor: u along +x (width 4), v along -z (height 2), facing up.
  const TriangleMesh& floor = scene.meshes[1];
  expectNear(floor.positions[0], {-2, -1, 1});
  expectNear(floor.positions[1], {2, -1, 1});
  expectNear(floor.positions[3], {-2, -1, -1});
  expectNear(floor.normals[0], {0, 1, 0});
  expectOutwardWinding(floor, {0, -2, 0});
  // A square turned 45 degrees in its plane: its v edge runs along (1, 1, 0)/sqrt(2).
  const TriangleMesh& tilted = scene.meshes[2];
  const float h = std::sqrt(2.0f) / 2;
  expectNear(tilted.positions[3] - tilted.positions[0], {2 * h, 2 * h, 0});
  expectNear(tilted.positions[1] - tilted.positions[0], {2 * h, -2 * h, 0});
}

TEST_F(SceneFileTest, QuadLightsAndEmissiveObjectsBecomeLights) {
  const Scene scene = load(R"({
    "materials": {"glow": {"emission": 4}},
    "objects": [{"shape": "box", "size": 1, "material": "glow", "light_samples": 8,
                 "light_two_sided": true},
                {"shape": "sphere", "radius": 1, "center": [5, 0, 0], "material": "glow"},
                {"shape": "box", "size": 1, "center": [0, 3, 0]}],
    "lights": [{"type": "quad", "name": "lamp", "corner": [0, 4, 0], "edge_u": [1, 0, 0],
                "edge_v": [0, 0, 1], "radiance": [5, 6, 7], "samples": 4, "two_sided": true}]
  })");
  ASSERT_EQ(scene.lights.size(), 2u);
  const Light& quad = scene.lights[0];
  EXPECT_EQ(quad.kind, Light::Kind::Quad);
  EXPECT_EQ(quad.edgeV, Vec3f(0, 0, 1));
  EXPECT_EQ(quad.samples, 4);
  EXPECT_TRUE(quad.twoSided);
  ASSERT_EQ(quad.mesh, 2);
  const TriangleMesh& lampMesh = scene.meshes[2];
  EXPECT_EQ(lampMesh.positions[2], Vec3f(1, 4, 1));
  EXPECT_EQ(scene.materials[lampMesh.material].emission, Vec3f(5, 6, 7));
  EXPECT_EQ(scene.materials[lampMesh.material].name, "lamp");
  const Light& box = scene.lights[1];
  EXPECT_EQ(box.kind, Light::Kind::Mesh);
  EXPECT_EQ(box.mesh, 0);
  EXPECT_EQ(box.intensity, Vec3f(4.0f));
  EXPECT_EQ(box.samples, 8);
  EXPECT_TRUE(box.twoSided);
  ASSERT_EQ(scene.warnings.size(), 1u);  // the glowing sphere lights nothing
  EXPECT_NE(scene.warnings[0].find("/objects/1"), std::string::npos);
  // The display is placed from the objects only, not from the lamp above them.
  EXPECT_FLOAT_EQ(scene.display.center.y, 1.25f);
}

TEST_F(SceneFileTest, MeshObjectsLoadRelativeToTheSceneFile) {
  writeTriangleObj("models/tri.obj");
  const Scene scene = load(R"({
    "materials": {"blue": {"color": [0, 0, 1]}},
    "objects": [{"name": "t1", "shape": "mesh", "file": "models/tri.obj", "material": "blue",
                 "transform": [{"scale": 2}, {"translate": [0, 0, 1]}]},
                {"name": "t2", "shape": "mesh", "file": "models/tri.obj"}]})");
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].material, 0u);
  Bounds3f b;
  for (const Vec3f& p : scene.meshes[0].positions) b.extend(p);
  expectNear(b.lo, {0, 0, 1});
  expectNear(b.hi, {2, 2, 1});
  EXPECT_NE(scene.meshes[1].material, 0u);  // the file's own (default) material
  EXPECT_LT(scene.meshes[1].material, scene.materials.size());
}

TEST_F(SceneFileTest, BareMeshFilesGetLightsDisplayAndCamera) {
  writeTriangleObj("tri.obj");
  const Scene scene = loadScene((dir_ / "tri.obj").string());
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_FALSE(scene.materials.empty());
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_LT(scene.lights[0].direction.y, 0.0f);  // from above
  EXPECT_LT(scene.lights[0].direction.z, 0.0f);  // from the viewer's side
  EXPECT_GT(maxComponent(scene.ambient), 0.0f);
  expectNear(scene.display.center, {0.5f, 0.5f, 0});
  EXPECT_EQ(scene.display.normal, Vec3f(0, 0, 1));
  EXPECT_FLOAT_EQ(scene.display.width, 1.0f);
  EXPECT_TRUE(scene.display.fit);
  ASSERT_TRUE(scene.camera);
  EXPECT_EQ(scene.camera->eye, frameScene(scene).eye);
}

TEST_F(SceneFileTest, FileErrors) {
  try {
    loadScene((dir_ / "nope.json").string());
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir_ / "nope.json").string());
    EXPECT_NE(std::string(e.what()).find("file not found"), std::string::npos);
  }
  const std::string text = write("scene.txt", "{}");
  EXPECT_THROW(loadScene(text), InputError);
  expectError("{\"objects\": [}", "", "line 1, column 14");
  expectError("{\n  \"objects\": [\n    {\"shape\": \"sphere\"", "", "line 3");
  expectError("", "", "line 1");
  expectError(R"({"objects": [], "objects": []})", "/objects", "duplicate key");
  expectError(R"({"objects": [{"shape": "sphere", "radius": 1, "radius": 2}]})",
              "/objects/0/radius", "duplicate key");
  expectError("[1, 2]", "", "expected an object");
  expectError(R"({"version": 2})", "/version", "unsupported version 2");
}

TEST_F(SceneFileTest, KeyAndTypeErrorsNameTheJsonPointer) {
  expectError(R"({"objcts": []})", "/objcts", "unknown key (did you mean 'objects'?)");
  expectError(R"({"objects": [{"shape": "sphere", "radius": 1, "material": {"colr": 1}}]})",
              "/objects/0/material/colr", "unknown key (did you mean 'color'?)");
  expectError(R"({"objects": [{"shap": "sphere"}]})", "/objects/0/shap", "did you mean 'shape'?");
  expectError(R"({"objects": [{"shape": "sphere", "radius": 1, "edge_u": [1, 0, 0]}]})",
              "/objects/0/edge_u", "unknown key");
  expectError(R"({"objects": [{"shape": "sphre"}]})", "/objects/0/shape",
              "unknown shape 'sphre' (did you mean 'sphere'?)");
  expectError(R"({"objects": [{"shape": "sphere", "radius": 1}, {"shape": "sphere", "radius": 1},
    {"shape": "sphere", "radius": 1}, {"shape": "sphere", "radius": 1,
     "material": {"color": [1, 0]}}]})",
              "/objects/3/material/color", "expected 3 numbers");
  expectError(R"({"objects": [{"shape": "sphere", "radius": -1}]})", "/objects/0/radius",
              "expected a positive number");
  expectError(R"({"objects": [{"shape": "sphere"}]})", "/objects/0", "missing key 'radius'");
  expectError(R"({"objects": [{"shape": "sphere", "radius": 1, "center": [0, "a", 0]}]})",
              "/objects/0/center", "expected 3 numbers");
  expectError(R"({"ambient": "bright"})", "/ambient", "expected 3 numbers [r, g, b] or one number");
  expectError(R"({"materials": {"m": {"color": [2, 0, 0]}}})", "/materials/m/color", "at most 1");
  expectError(R"({"materials": {"a/b": {"mirror": -1}}})", "/materials/a~1b/mirror", ">= 0");
  expectError(R"({"max_depth": 2.5})", "/max_depth", "expected an integer");
  expectError(R"({"lights": [{"type": "spot"}]})", "/lights/0/type", "unknown light type");
  expectError(R"({"textures": {"t": {"type": "checker", "size": 0}}})", "/textures/t/size",
              "positive");
}

TEST_F(SceneFileTest, ReferenceErrors) {
  expectError(R"({"materials": {"red": {}}, "objects": [{"shape": "sphere", "radius": 1,
    "material": "rde"}]})",
              "/objects/0/material", "unknown material 'rde' (did you mean 'red'?)");
  expectError(R"({"objects": [{"shape": "sphere", "radius": 1, "material": "gold"}]})",
              "/objects/0/material", "no materials are defined");
  expectError(R"({"materials": {"m": {"texture": "wod"}}, "textures": {"wood": {"type":
    "checker"}}})",
              "/materials/m/texture", "did you mean 'wood'?");
  expectError(R"({"textures": {"t": {"type": "image", "file": "missing.png"}}})",
              "/textures/t/file", "image file not found");
  write("broken.png", "not a png");
  expectError(R"({"textures": {"t": {"type": "image", "file": "broken.png"}}})", "/textures/t/file",
              "not a readable image");
  const std::string missing = (dir_ / "meshes" / "gone.obj").string();
  expectError(R"({"objects": [{"shape": "mesh", "file": "meshes/gone.obj"}]})", "/objects/0/file",
              "mesh file not found: " + missing);
  write("notes.txt", "hello");
  expectError(R"({"objects": [{"shape": "mesh", "file": "notes.txt"}]})", "/objects/0/file",
              "not a mesh file");
}

TEST_F(SceneFileTest, GeometryErrors) {
  expectError(R"({"objects": [{"shape": "sphere", "radius": 1, "transform": [{"scale": 0}]}]})",
              "/objects/0/transform/0/scale", "singular");
  expectError(R"({"objects": [{"shape": "box", "size": 1, "transform": {"matrix":
    [1, 0, 0, 0,  0, 1, 0, 0,  1, 1, 0, 0,  0, 0, 0, 1]}}]})",
              "/objects/0/transform/matrix", "singular");
  expectError(R"({"objects": [{"shape": "box", "size": 1, "transform": {"matrix":
    [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 1, 1]}}]})",
              "/objects/0/transform/matrix", "last row");
  expectError(R"({"objects": [{"shape": "box", "size": 1, "transform": {"matrix": [1, 2, 3]}}]})",
              "/objects/0/transform/matrix", "expected 16 numbers");
  expectError(R"({"objects": [{"shape": "box", "size": 1, "transform": [{"spin": 1}]}]})",
              "/objects/0/transform/0/spin", "unknown key");
  expectError(R"({"objects": [{"shape": "box", "size": 1,
    "transform": [{"translate": [1, 0, 0], "scale": 2}]}]})",
              "/objects/0/transform/0", "exactly one");
  expectError(R"({"objects": [{"shape": "box", "size": 1,
    "transform": [{"rotate": {"angle": 10, "axis": [0, 0, 0]}}]}]})",
              "/objects/0/transform/0/rotate/axis", "non-zero");
  expectError(
      R"({"objects": [{"shape": "sphere", "radius": 1, "transform": [{"scale": [1, 2, 1]}]}]})",
      "/objects/0/transform", "scaled uniformly");
  expectError(R"({"objects": [{"shape": "box", "min": [0, 0, 0], "max": [1, 0, 1]}]})",
              "/objects/0/max", "must exceed");
  expectError(R"({"objects": [{"shape": "box", "size": 1, "min": [0, 0, 0], "max": [1, 1, 1]}]})",
              "/objects/0/size", "either");
  expectError(R"({"objects": [{"shape": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0],
    "edge_v": [2, 0, 0]}]})",
              "/objects/0", "zero-area quad");
  expectError(
      R"({"objects": [{"shape": "plane", "normal": [0, 1, 0], "up": [0, 2, 0], "size": 1}]})",
      "/objects/0/up", "parallel");
  expectError(R"({"lights": [{"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0],
    "edge_v": [0, 0, 0], "radiance": 1}]})",
              "/lights/0", "zero-area quad light");
  expectError(R"({"lights": [{"type": "directional", "direction": [0, 0, 0], "irradiance": 1}]})",
              "/lights/0/direction", "non-zero");
  expectError(R"({"camera": {"eye": [0, 0, 1], "look_at": [0, 0, 1]}})", "/camera/look_at",
              "equals");
  expectError(R"({"camera": {"eye": [0, 5, 0], "look_at": [0, 0, 0]}})", "/camera",
              "'up' is parallel to the viewing direction");
  expectError(R"({"camera": {"eye": [0, 0, 1], "look_at": [0, 0, 0], "fov": 180}})", "/camera/fov",
              "between 0 and 180");
  expectError(R"({"display": {"normal": [0, 0, 1], "up": [0, 0, -3]}})", "/display/up", "parallel");
  expectError(R"({"display": {"width": 0}})", "/display/width", "positive");
}

// The built-in scene and scenes/checker-box.json describe the same scene by different paths.
TEST(ExampleScenes, CheckerBoxFileMatchesTheBuiltInScene) {
  const Scene file = loadScene(PARALLAX_SOURCE_DIR "/scenes/checker-box.json");
  const Scene builtIn = defaultScene();
  ASSERT_EQ(file.meshes.size(), builtIn.meshes.size());
  for (size_t m = 0; m < file.meshes.size(); ++m) {
    ASSERT_EQ(file.meshes[m].positions.size(), builtIn.meshes[m].positions.size());
    EXPECT_EQ(file.meshes[m].indices, builtIn.meshes[m].indices);
    for (size_t i = 0; i < file.meshes[m].positions.size(); ++i) {
      expectNear(file.meshes[m].positions[i], builtIn.meshes[m].positions[i]);
      expectNear(file.meshes[m].normals[i], builtIn.meshes[m].normals[i]);
    }
    const Material& a = file.materials[file.meshes[m].material];
    const Material& b = builtIn.materials[builtIn.meshes[m].material];
    EXPECT_EQ(a.diffuse, b.diffuse);
    EXPECT_EQ(a.emission, b.emission);
    EXPECT_EQ(a.diffuseTexture >= 0, b.diffuseTexture >= 0);
  }
  ASSERT_EQ(file.textures.size(), builtIn.textures.size());
  EXPECT_EQ(file.textures[0].color, builtIn.textures[0].color);
  EXPECT_EQ(file.textures[0].color2, builtIn.textures[0].color2);
  EXPECT_EQ(file.textures[0].checkerSize, builtIn.textures[0].checkerSize);
  ASSERT_EQ(file.lights.size(), builtIn.lights.size());
  EXPECT_EQ(file.lights[0].kind, builtIn.lights[0].kind);
  EXPECT_EQ(file.lights[0].corner, builtIn.lights[0].corner);
  EXPECT_EQ(file.lights[0].intensity, builtIn.lights[0].intensity);
  EXPECT_EQ(file.lights[0].mesh, builtIn.lights[0].mesh);
  EXPECT_EQ(file.ambient, builtIn.ambient);
  EXPECT_EQ(file.background, builtIn.background);
  EXPECT_EQ(file.display.center, builtIn.display.center);
  EXPECT_EQ(file.display.width, builtIn.display.width);
  ASSERT_TRUE(file.camera);
  EXPECT_EQ(file.camera->eye, builtIn.camera->eye);
  EXPECT_EQ(file.camera->lookAt, builtIn.camera->lookAt);
  EXPECT_EQ(file.camera->fovDegrees, builtIn.camera->fovDegrees);
}

TEST(ExampleScenes, AllLoadWithoutWarnings) {
  size_t count = 0;
  for (const auto& entry : fs::directory_iterator(PARALLAX_SOURCE_DIR "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    SCOPED_TRACE(entry.path().string());
    const Scene scene = loadScene(entry.path().string());
    EXPECT_GT(scene.meshes.size() + scene.spheres.size(), 0u);
    EXPECT_FALSE(scene.lights.empty());
    // A one-sided quad light that faced away from the scene would light nothing.
    for (const Light& light : scene.lights) {
      if (light.kind != Light::Kind::Quad || light.twoSided) continue;
      const Vec3f lightCenter = light.corner + (light.edgeU + light.edgeV) * 0.5f;
      EXPECT_GT(dot(cross(light.edgeU, light.edgeV), scene.display.center - lightCenter), 0);
    }
    // Mesh files may warn about their own contents; the scene file itself must not.
    for (const std::string& warning : scene.warnings)
      EXPECT_NE(warning.rfind(entry.path().string(), 0), 0u) << warning;
  }
  EXPECT_GE(count, 5u);
}

}  // namespace
}  // namespace parallax

namespace parallax {
namespace {

TEST_F(SceneFileTest, DisplayFramingKeys) {
  const Scene scene = load(R"({"objects": [
    {"shape": "sphere", "center": [0, 0, 0], "radius": 1},
    {"shape": "plane", "center": [0, -1, 0], "size": 40}],
    "display": {"width": 3, "fit": "depth", "focus": -12.5, "depth_budget": 20}})");
  EXPECT_EQ(scene.display.fitMode, DisplayFit::Depth);
  ASSERT_TRUE(scene.display.focusMm);
  EXPECT_DOUBLE_EQ(*scene.display.focusMm, -12.5);
  ASSERT_TRUE(scene.display.depthBudgetMm);
  EXPECT_DOUBLE_EQ(*scene.display.depthBudgetMm, 20.0);
  // The content the framing measures leaves out the plane (a floor recedes on purpose).
  ASSERT_TRUE(scene.display.content);
  expectNear(scene.display.content->lo, {-1, -1, -1});
  expectNear(scene.display.content->hi, {1, 1, 1});
  const Scene automatic = load(R"({"objects": [{"shape": "sphere", "radius": 1}],
    "display": {"fit": "auto", "focus": "auto", "depth_budget": "auto"}})");
  EXPECT_EQ(automatic.display.fitMode, DisplayFit::Auto);
  EXPECT_FALSE(automatic.display.focusMm);
  EXPECT_FALSE(automatic.display.depthBudgetMm);
}

TEST_F(SceneFileTest, DisplayFramingKeysAreChecked) {
  const std::string sphere = R"({"objects": [{"shape": "sphere", "radius": 1}], "display": )";
  expectError(sphere + R"({"fit": "wide"}})", "/display/fit", "expected window, depth");
  expectError(sphere + R"({"focus": "near"}})", "/display/focus", "auto");
  expectError(sphere + R"({"focus": 1e5}})", "/display/focus", "10000 mm");
  expectError(sphere + R"({"depth_budget": 0}})", "/display/depth_budget", "above 0");
  expectError(sphere + R"({"depth_budget": 5000}})", "/display/depth_budget", "1000 mm");
  expectError(sphere + R"({"depth_budget": true}})", "/display/depth_budget", "millimetres");
  expectError(sphere + R"({"depth": 3}})", "/display/depth", "unknown key");
}

}  // namespace
}  // namespace parallax
