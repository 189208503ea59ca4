// A packet's lanes are independent: tracing sixteen rays together gives, lane by lane, what
// each ray gives alone in an otherwise empty packet (shadows, mirrors and light sampling).
#include "parallax/render/packet_tracer.h"

#include <gtest/gtest.h>

namespace parallax {
namespace {

TEST(PacketTracer, LanesDoNotDependOnTheirNeighbours) {
  Scene scene = defaultScene();
  Material mirror;
  mirror.diffuse = Vec3f(0.5f);
  mirror.mirror = Vec3f(0.5f);
  scene.materials.push_back(mirror);
  scene.spheres.push_back({"ball", uint32_t(scene.materials.size() - 1), {1.2f, 0.0f, 0.2f}, 0.5f});
  const Accelerator accel(scene);
  const LightSampler lights(scene);
  const PacketTracer tracer(scene, accel, lights);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 64, 36);

  Color16 weight;
  weight.fill(1.0f);
  for (int block = 0; block < 40; ++block) {
    RayPacket16 packet;
    std::array<Rng, 16> rngs;
    for (int lane = 0; lane < 16; ++lane) {
      const int x = (block * 7 + lane * 3) % 64, y = (block * 5 + lane) % 36;
      packet.set(lane, camera.generateRay({x + 0.5f, y + 0.5f}));
      rngs[size_t(lane)] = Rng::forSample(uint32_t(x), uint32_t(y), 0);
    }
    Color16 together;
    together.fill(0.0f);
    RenderStats stats;
    tracer.trace(packet, weight, rngs, together, 0, stats);
    for (int lane = 0; lane < 16; ++lane) {
      RayPacket16 single;
      for (int other = 0; other < 16; ++other) single.deactivate(other);
      single.set(lane, packet.ray(lane));
      std::array<Rng, 16> singleRngs;
      const int x = (block * 7 + lane * 3) % 64, y = (block * 5 + lane) % 36;
      singleRngs[size_t(lane)] = Rng::forSample(uint32_t(x), uint32_t(y), 0);
      Color16 alone;
      alone.fill(0.0f);
      tracer.trace(single, weight, singleRngs, alone, 0, stats);
      EXPECT_EQ(together.at(lane), alone.at(lane)) << "block " << block << " lane " << lane;
    }
  }
}

}  // namespace
}  // namespace parallax
