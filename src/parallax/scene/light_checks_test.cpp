// lightFacingWarnings against scenes whose answer is known by construction: a lamp above a
// floor facing it or away from it, two-sided, and spots aimed at or away from a box.
#include "parallax/scene/light_checks.h"

#include <gtest/gtest.h>

namespace parallax {
namespace {

Scene floorScene() {
  Scene scene;
  scene.materials.push_back(Material{});
  addBox(scene, "floor", {-2, -0.1f, -2}, {2, 0, 2}, 0);
  return scene;
}

// A quad light at y = 2; its front face (cross(edgeU, edgeV)) points down if `down`.
Light quadLight(bool down) {
  Light light;
  light.kind = Light::Kind::Quad;
  light.corner = {-0.5f, 2, -0.5f};
  light.edgeU = down ? Vec3f(1, 0, 0) : Vec3f(0, 0, 1);
  light.edgeV = down ? Vec3f(0, 0, 1) : Vec3f(1, 0, 0);
  return light;
}

TEST(LightChecks, QuadLightFacingTheFloorIsFine) {
  Scene scene = floorScene();
  scene.lights.push_back(quadLight(true));
  ASSERT_LT(cross(scene.lights[0].edgeU, scene.lights[0].edgeV).y, 0.0f);
  EXPECT_TRUE(lightFacingWarnings(scene).empty());
}

TEST(LightChecks, QuadLightFacingAwayIsWarnedUnlessTwoSided) {
  Scene scene = floorScene();
  scene.lights.push_back(quadLight(false));
  const auto warnings = lightFacingWarnings(scene);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("light 0"), std::string::npos) << warnings[0];
  scene.lights[0].twoSided = true;
  EXPECT_TRUE(lightFacingWarnings(scene).empty());
}

TEST(LightChecks, MeshLightIsJudgedByItsTrianglesAndIgnoresItself) {
  for (const bool down : {true, false}) {
    Scene scene = floorScene();
    const Light q = quadLight(down);
    addQuad(scene, "lamp", q.corner, q.edgeU, q.edgeV, 0);
    Light light;
    light.kind = Light::Kind::Mesh;
    light.mesh = int(scene.meshes.size()) - 1;
    scene.lights.push_back(light);
    const auto warnings = lightFacingWarnings(scene);
    EXPECT_EQ(warnings.size(), down ? 0u : 1u) << "down " << down;
    if (!down) {
      EXPECT_NE(warnings[0].find("'lamp'"), std::string::npos) << warnings[0];
    }
  }
}

TEST(LightChecks, SpotMustHaveSomethingInItsCone) {
  Scene scene = floorScene();
  Light spot;
  spot.kind = Light::Kind::Spot;
  spot.position = {0, 2, 0};
  spot.outerCone = 0.3f;
  scene.lights.push_back(spot);
  for (const auto& [direction, warned] :
       {std::pair{Vec3f(0, -1, 0), false}, std::pair{Vec3f(0, 1, 0), true},
        // Sideways: the floor's corner (2, 0, 0) is atan(2 / 2) = 45 degrees below the
        // horizontal; a 0.3 rad cone along +x misses it, a wide one does not.
        std::pair{Vec3f(1, 0, 0), true}}) {
    scene.lights[0].direction = direction;
    EXPECT_EQ(lightFacingWarnings(scene).size(), warned ? 1u : 0u)
        << direction.x << "," << direction.y << "," << direction.z;
  }
  scene.lights[0].outerCone = 1.2f;  // 69 degrees: reaches the floor
  EXPECT_TRUE(lightFacingWarnings(scene).empty());
}

TEST(LightChecks, PointAndDirectionalLightsAndEmptyScenesAreNotJudged) {
  Scene scene;
  scene.lights.push_back(quadLight(false));  // nothing else in the scene
  Light point;
  scene.lights.push_back(point);
  EXPECT_TRUE(lightFacingWarnings(scene).empty());
}

}  // namespace
}  // namespace parallax
