#include "parallax/camera/display_camera.h"

#include "parallax/core/lane_kernel.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace parallax {

namespace {
Vec3f toFloat(const Vec3d& v) {
  return {float(v.x), float(v.y), float(v.z)};
}
}  // namespace

namespace {

// The display's axes in the scene: x = up x normal, y = up, z = normal (unit).
struct DisplayAxes {
  Vec3f right, up, normal;
  explicit DisplayAxes(const DisplayPlacement& placement)
      : right(normalize(cross(placement.up, normalize(placement.normal)))),
        up(cross(normalize(placement.normal), right)),
        normal(normalize(placement.normal)) {}
};

// True if every corner of `corners` (display axes, scene units from the display's centre) seen
// from the window's eye at `mmPerUnit` lands inside the window, `margin` in from each edge.
bool fitsInside(const std::vector<Vec3d>& corners, const DisplayWindow& window, double mmPerUnit,
                double margin) {
  const Vec3d& e = window.eyeMm;
  const double halfW = 0.5 * window.widthMm * (1 - 2 * margin);
  const double halfH = 0.5 * window.heightMm * (1 - 2 * margin);
  for (const Vec3d& c : corners) {
    const double x = c.x * mmPerUnit, y = c.y * mmPerUnit, z = c.z * mmPerUnit;
    if (!(z < e.z)) return false;  // at or behind the eye
    // The line from the eye through the corner meets the front layer (z = 0) at e + (p - e) s.
    const double s = e.z / (e.z - z);
    if (std::abs(e.x + (x - e.x) * s) > halfW || std::abs(e.y + (y - e.y) * s) > halfH)
      return false;
  }
  return true;
}

}  // namespace

float fitDisplayWidth(const DisplayPlacement& placement, const DisplayWindow& window) {
  if (!placement.fit || placement.fit->empty()) return placement.width;
  const DisplayAxes axes(placement);
  std::vector<Vec3d> corners;
  for (int i = 0; i < 8; ++i) {
    const Bounds3f& b = *placement.fit;
    const Vec3f p{i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z};
    const Vec3f d = p - placement.center;
    corners.push_back({dot(d, axes.right), dot(d, axes.up), dot(d, axes.normal)});
  }
  constexpr double margin = 0.05;
  // Bigger scales push the corners outward; find the largest that still fits by bisection
  // between a scale that fits and one that does not.
  double fits = window.widthMm / placement.width * 1e-6;
  if (!fitsInside(corners, window, fits, margin)) return placement.width;  // eye off the window
  double fails = fits;
  for (int i = 0; i < 80 && fitsInside(corners, window, fails, margin); ++i) fails *= 2;
  if (fitsInside(corners, window, fails, margin)) return placement.width;  // a flat point
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (fits + fails);
    (fitsInside(corners, window, mid, margin) ? fits : fails) = mid;
  }
  return float(window.widthMm / fits);
}

Transform worldFromDisplay(const DisplayPlacement& placement, const DisplayWindow& window) {
  const DisplayAxes axes(placement);
  Mat4 m = Mat4::identity();
  const float scale = fitDisplayWidth(placement, window) / float(window.widthMm);
  for (int i = 0; i < 3; ++i) {
    m.m[i][0] = axes.right[i] * scale;
    m.m[i][1] = axes.up[i] * scale;
    m.m[i][2] = axes.normal[i] * scale;
    m.m[i][3] = placement.center[i];
  }
  return Transform(m);
}

DisplayCamera::DisplayCamera(const DisplayModel& display, const DisplayPlacement& placement)
    : display_(&display),
      film_(display.film()),
      worldFromDisplay_(worldFromDisplay(placement, display.window())) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) affine_[r][c] = worldFromDisplay_.matrix().m[r][c];
}

DisplayCamera::DisplayCamera(std::unique_ptr<DisplayModel> display,
                             const DisplayPlacement& placement)
    : DisplayCamera(*display, placement) {
  owned_ = std::move(display);
}

namespace {

// generateRays16's lane loop: display rays (double, display mm) into the world (float) by the
// affine map m. Outside the class: GCC cannot make ISA clones of a virtual function
// (core/lane_kernel.h).
PARALLAX_LANE_KERNEL void worldRays16(const float affine[3][4], const double origin[3][16],
                                      const double direction[3][16], RayPacket16& __restrict out) {
  // A local copy of the matrix and a restricted packet: no store to the packet can change what
  // the loop reads, so it vectorises.
  float m[3][4];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m[r][c] = affine[r][c];
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

}  // namespace

void DisplayCamera::generateRays16(const FilmSamples16& s, RayPacket16& out) const {
  alignas(64) double origin[3][16], direction[3][16];
  display_->rays16(s.x, s.y, s.apertureU, s.apertureV, origin, direction);
  worldRays16(affine_, origin, direction, out);
}

Ray DisplayCamera::generateRay(const FilmSample& s) const {
  const DisplayRay r = display_->ray(s.x, s.y, s.apertureU, s.apertureV);
  return {worldFromDisplay_.point(toFloat(r.origin)),
          worldFromDisplay_.vector(toFloat(r.direction))};
}

PacketShape DisplayCamera::packetShape() const {
  // Rays that do not fan through a shared aperture (a lenticular's subpixels, each in its own
  // direction) are best packed as neighbouring pixels, like any camera's.
  if (!display_->columnFans()) return {4, 4, 1, false, true};
  // One film column, sixteen rows: a fan of rays in one vertical plane through one aperture,
  // which traverses the BVH like a pinhole camera's column of pixels. Columns of the same view
  // lie a whole screen period apart (9 px by default), so a wider packet would spread over
  // several millimetres of scene and cost Embree more (docs/architecture.md, "Speed").
  // The fan stays parallel under super-sampling only if its lanes share their jitter: the
  // aperture jitter alone turns a ray by up to a quarter period over the gap (0.2 rad).
  return {1, 16, 1, true, true};
}

WindowCamera::WindowCamera(const Vec3d& eyeMm, const DisplayModel& display,
                           const DisplayPlacement& placement, int width, int height,
                           bool horizontalOnly)
    : width_(width), height_(height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("camera size must be positive");
  if (!(eyeMm.z > 0))
    throw std::invalid_argument("the eye must be in front of the display (z > 0)");
  const DisplayWindow window = display.window();
  const Transform world = worldFromDisplay(placement, window);
  const float w = float(window.widthMm), h = float(window.heightMm);
  const Vec3d eyeSeen = display.intendedEye(eyeMm);
  p_.eye = world.point(toFloat(eyeSeen));
  p_.corner = world.point({-0.5f * w, 0.5f * h, 0.0f});
  p_.stepX = world.vector({w / float(width), 0.0f, 0.0f});
  p_.stepY = world.vector({0.0f, -h / float(height), 0.0f});
  p_.up = world.vector({0.0f, 1.0f, 0.0f});
  p_.frontHalfHeight = 0.5f * h;
  p_.rowStepMm = h / float(height);
  p_.viewLineY = float(window.eyeMm.y);
  p_.eyeHeight = float(eyeMm.y);
  p_.depthRatio = float(eyeSeen.z) / float(window.eyeMm.z);
  p_.horizontalOnly = horizontalOnly;
}

namespace {

// WindowCamera's rays, generateRay's formulas in the same order for 16 lanes (a loop outside the
// class: GCC cannot make ISA clones of a virtual function, core/lane_kernel.h). With
// `horizontalOnly` the origin moves along the display's up by `shift` (generateRay's
// originY - eyeHeight); without, shift is 0 and the origin is the eye. The constants are read
// in place (a copy of them per packet, made field by field on the stack and read back whole,
// stalled on store forwarding) and the ratio of depths is one product (a division per packet
// was a tenth of the camera's time).
PARALLAX_LANE_KERNEL void windowRays16(const WindowRayParameters& p, const FilmSamples16& s,
                                       RayPacket16& __restrict out) {
  for (int i = 0; i < 16; ++i) {
    const float tx = p.corner.x + p.stepX.x * s.x[i] + p.stepY.x * s.y[i];
    const float ty = p.corner.y + p.stepX.y * s.x[i] + p.stepY.y * s.y[i];
    const float tz = p.corner.z + p.stepX.z * s.x[i] + p.stepY.z * s.y[i];
    const float frontY = p.frontHalfHeight - s.y[i] * p.rowStepMm;
    const float originY = frontY + (p.viewLineY - frontY) * p.depthRatio;
    const float shift = p.horizontalOnly ? originY - p.eyeHeight : 0.0f;
    const float ox = p.eye.x + p.up.x * shift, oy = p.eye.y + p.up.y * shift,
                oz = p.eye.z + p.up.z * shift;
    out.ox[i] = ox, out.oy[i] = oy, out.oz[i] = oz;
    out.dx[i] = tx - ox, out.dy[i] = ty - oy, out.dz[i] = tz - oz;
    out.tMin[i] = 0.0f;
    out.tMax[i] = std::numeric_limits<float>::infinity();
  }
}

}  // namespace

void WindowCamera::generateRays16(const FilmSamples16& s, RayPacket16& out) const {
  windowRays16(p_, s, out);
}

Ray WindowCamera::generateRay(const FilmSample& s) const {
  const Vec3f target = p_.corner + p_.stepX * s.x + p_.stepY * s.y;
  if (!p_.horizontalOnly) return {p_.eye, target - p_.eye};
  // The line through the front point F at height y_F: x toward the eye, y toward the view
  // line, so at the eye's depth it is (x_e, y_F + (y_e - y_F) z_e / D).
  const float frontY = p_.frontHalfHeight - s.y * p_.rowStepMm;
  const float originY = frontY + (p_.viewLineY - frontY) * p_.depthRatio;
  // eye sits at the eye's height; move the origin along the display's up to originY.
  const Vec3f origin = p_.eye + p_.up * (originY - p_.eyeHeight);
  return {origin, target - origin};
}

}  // namespace parallax
