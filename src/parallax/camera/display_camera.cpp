#include "parallax/camera/display_camera.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace parallax {

namespace {
Vec3f toFloat(const Vec3d& v) {
  return {float(v.x), float(v.y), float(v.z)};
}
}  // namespace

Transform worldFromDisplay(const DisplayPlacement& placement, double frontWidthMm) {
  const Vec3f normal = normalize(placement.normal);
  const Vec3f right = normalize(cross(placement.up, normal));
  const Vec3f up = cross(normal, right);
  Mat4 m = Mat4::identity();
  const float scale = float(placement.width / frontWidthMm);
  for (int i = 0; i < 3; ++i) {
    m.m[i][0] = right[i] * scale;
    m.m[i][1] = up[i] * scale;
    m.m[i][2] = normal[i] * scale;
    m.m[i][3] = placement.center[i];
  }
  return Transform(m);
}

DisplayCamera::DisplayCamera(const DisplayDesign& design, const DisplayPlacement& placement)
    : rays_(design), worldFromDisplay_(worldFromDisplay(placement, design.frontWidthMm())) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) affine_[r][c] = worldFromDisplay_.matrix().m[r][c];
}

void DisplayCamera::generateRays16(const FilmSamples16& s, RayPacket16& out) const {
  alignas(64) double origin[3][16], direction[3][16];
  rays_.rays16(s.x, s.y, s.apertureU, s.apertureV, origin, direction);
  // A local copy of the matrix: the packet cannot alias it, so the loop vectorises.
  float m[3][4];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m[r][c] = affine_[r][c];
  for (int i = 0; i < 16; ++i) {
    const float x = float(origin[0][i]), y = float(origin[1][i]), z = float(origin[2][i]);
    const float dx = float(direction[0][i]), dy = float(direction[1][i]);
    const float dz = float(direction[2][i]);
    out.ox[i] = m[0][0] * x + m[0][1] * y + m[0][2] * z + m[0][3];
    out.oy[i] = m[1][0] * x + m[1][1] * y + m[1][2] * z + m[1][3];
    out.oz[i] = m[2][0] * x + m[2][1] * y + m[2][2] * z + m[2][3];
    out.dx[i] = m[0][0] * dx + m[0][1] * dy + m[0][2] * dz;
    out.dy[i] = m[1][0] * dx + m[1][1] * dy + m[1][2] * dz;
    out.dz[i] = m[2][0] * dx + m[2][1] * dy + m[2][2] * dz;
    out.tMin[i] = 0.0f;
    out.tMax[i] = std::numeric_limits<float>::infinity();
  }
}

Ray DisplayCamera::generateRay(const FilmSample& s) const {
  const BarrierRay r = rays_.ray(s.x, s.y, s.apertureU, s.apertureV);
  return {worldFromDisplay_.point(toFloat(r.origin)),
          worldFromDisplay_.vector(toFloat(r.direction))};
}

PacketShape DisplayCamera::packetShape() const {
  // One film column, sixteen rows: a fan of rays in one vertical plane through one aperture,
  // which traverses the BVH like a pinhole camera's column of pixels. Columns of the same view
  // lie a whole screen period apart (9 px by default), so a wider packet would spread over
  // several millimetres of scene and cost Embree more (docs/architecture.md, "Speed").
  // The fan stays parallel under super-sampling only if its lanes share their jitter: the
  // aperture jitter alone turns a ray by up to a quarter period over the gap (0.2 rad).
  return {1, 16, 1, true};
}

WindowCamera::WindowCamera(const Vec3d& eyeMm, const DisplayDesign& design,
                           const DisplayPlacement& placement, int width, int height,
                           bool horizontalOnly)
    : width_(width), height_(height), horizontalOnly_(horizontalOnly) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("camera size must be positive");
  if (!(eyeMm.z > 0))
    throw std::invalid_argument("the eye must be in front of the display (z > 0)");
  const Transform world = worldFromDisplay(placement, design.frontWidthMm());
  const float w = float(design.frontWidthMm()), h = float(design.frontHeightMm());
  eye_ = world.point(toFloat(eyeMm));
  corner_ = world.point({-0.5f * w, 0.5f * h, 0.0f});
  stepX_ = world.vector({w / float(width), 0.0f, 0.0f});
  stepY_ = world.vector({0.0f, -h / float(height), 0.0f});
  worldUp_ = world.vector({0.0f, 1.0f, 0.0f});
  eyeZ_ = float(eyeMm.z);
  eyeHeight_ = float(eyeMm.y);
  frontHalfHeight_ = 0.5f * h;
  viewLineY_ = float(design.spec.viewZoneHeightMm);
  viewDistance_ = float(design.viewDistanceMm);
}

Ray WindowCamera::generateRay(const FilmSample& s) const {
  const Vec3f target = corner_ + stepX_ * s.x + stepY_ * s.y;
  if (!horizontalOnly_) return {eye_, target - eye_};
  // The line through the front point F at height y_F: x toward the eye, y toward the view
  // line, so at the eye's depth it is (x_e, y_F + (y_e - y_F) z_e / D).
  const float frontY = frontHalfHeight_ - s.y * (2.0f * frontHalfHeight_ / float(height_));
  const float originY = frontY + (viewLineY_ - frontY) * eyeZ_ / viewDistance_;
  // eye_ sits at the eye's height; move the origin along the display's up to originY.
  const Vec3f origin = eye_ + worldUp_ * (originY - eyeHeight_);
  return {origin, target - origin};
}

}  // namespace parallax
