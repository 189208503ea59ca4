// Cameras turn a position on the film into a ray. The render loop asks for rays in packets of
// sixteen so that a camera can lay out coherent rays; the default does it lane by lane.
#pragma once

#include "parallax/core/ray.h"

namespace parallax {

// A point on the film in continuous pixel coordinates: (0, 0) is the top-left corner of the
// top-left pixel, (width, height) the bottom-right corner. `aperture` is a second 2-D sample
// in [0,1)^2 for cameras that integrate over an aperture (the display camera's slit cell).
struct FilmSample {
  float x = 0.5f, y = 0.5f;
  float apertureU = 0.5f, apertureV = 0.5f;
};

// Sixteen film samples, structure of arrays.
struct alignas(64) FilmSamples16 {
  float x[16], y[16], apertureU[16], apertureV[16];
  FilmSample at(int lane) const { return {x[lane], y[lane], apertureU[lane], apertureV[lane]}; }
};

// A packet's pixels: `columns` x `rows` (16 in all), its columns `stride` film columns apart.
// The default, a 4 x 4 block of neighbouring pixels, suits any camera with one eye.
// `shareJitter`: the camera's rays stay parallel across the packet only if its lanes share
// the sub-pixel and aperture jitter (the display camera), so the render loop shares it.
// `aperture`: the camera reads the film samples' aperture coordinates (the display camera: where
// in its slit or lens a ray passes); the others ignore them, and the render loop does not draw
// them (it skips their draws, so every other random number stays the same).
struct PacketShape {
  int columns = 4, rows = 4, stride = 1;
  bool shareJitter = false;
  bool aperture = false;
};

class Camera {
 public:
  virtual ~Camera() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual Ray generateRay(const FilmSample& sample) const = 0;
  // The rays of the active lanes of `out` (whose `active` flags the caller has set).
  virtual void generateRays16(const FilmSamples16& samples, RayPacket16& out) const {
    for (int lane = 0; lane < 16; ++lane)
      if (out.active[lane]) out.set(lane, generateRay(samples.at(lane)));
  }
  // Which film pixels share a 16-ray packet, so that Embree traverses coherent rays.
  virtual PacketShape packetShape() const { return {}; }
};

// An ideal pinhole camera looking from `eye` at `lookAt`, with a vertical field of view.
class PinholeCamera final : public Camera {
 public:
  PinholeCamera(const Vec3f& eye, const Vec3f& lookAt, const Vec3f& up, float fovDegrees, int width,
                int height);

  int width() const override { return width_; }
  int height() const override { return height_; }
  Ray generateRay(const FilmSample& sample) const override {
    const Vec3f direction = pixel00_ + pixelDx_ * sample.x + pixelDy_ * sample.y;
    return {eye_, direction};
  }
  void generateRays16(const FilmSamples16& samples, RayPacket16& out) const override;

  // The film, as a point and two steps: the ray through film (x, y) has direction
  // pixel00 + x * pixelDx + y * pixelDy (unnormalised). Used by the benchmark's raw limit.
  PinholeGrid grid(int samplesPerPixel) const;

 private:
  Vec3f eye_, pixel00_, pixelDx_, pixelDy_;
  int width_, height_;
};

}  // namespace parallax
