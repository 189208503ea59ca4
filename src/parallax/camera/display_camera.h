// Cameras tied to the display: the parallax-barrier camera that renders the image layer, and
// the ideal off-axis view through the display's window from one eye (`view --display-eye`).
#pragma once

#include "parallax/camera/camera.h"
#include "parallax/core/transform.h"
#include "parallax/display/barrier_rays.h"
#include "parallax/scene/scene.h"

namespace parallax {

// The window a viewer looks through: the front layer's size, and the eye that content is
// framed for (the view-zone centre), in display millimetres.
struct DisplayWindow {
  double widthMm = 0, heightMm = 0;
  Vec3d eyeMm;
};
DisplayWindow displayWindow(const DisplayDesign& design);

// The placement's width for this window: placement.width, unless placement.fit is set; then
// the smallest width (the largest picture) at which every corner of the fit bounds, seen from
// the eye, falls inside the window with a 5 % margin on each side. Content pops out toward the
// eye, so this also keeps the near half of a deep object from filling the view.
float fitDisplayWidth(const DisplayPlacement& placement, const DisplayWindow& window);

// Display millimetres (docs/display-geometry.md) to scene units: the front layer's centre goes
// to placement.center, x to right = up x normal, y to up, z to normal, and the front layer's
// width in mm to fitDisplayWidth() scene units.
Transform worldFromDisplay(const DisplayPlacement& placement, const DisplayWindow& window);

// The eye whose picture of the scene a display rendered with a virtual gap g' != g (and
// D' = D) shows to an eye at `eyeMm` (display mm): the camera's rays, traced in the scene,
// meet the eye plane z = D at e_c + r (E - e_c) instead of E, r = g (g' + D) / (g' (g + D))
// for barrier-back and g / g' for barrier-front, and a point at z lands at
// z' = z D / (r (D - z) + z), x' = e_c + r (x - e_c) z' / z: the view-zone centre is its own
// virtual eye. The eye itself for g' = g or D' != D (docs/display-geometry.md, "Depth budget").
Vec3d virtualEye(const DisplayDesign& design, const Vec3d& eyeMm);

// One ray per image-layer film column (pixel, or subpixel in subpixel mode) through its
// aperture; see BarrierRayGenerator for the geometry.
class DisplayCamera final : public Camera {
 public:
  DisplayCamera(const DisplayDesign& design, const DisplayPlacement& placement,
                const ViewFilter& filter = {});

  int width() const override { return rays_.filmWidth(); }
  int height() const override { return rays_.filmHeight(); }
  Ray generateRay(const FilmSample& sample) const override;
  void generateRays16(const FilmSamples16& samples, RayPacket16& out) const override;
  PacketShape packetShape() const override;

  const BarrierRayGenerator& rays() const { return rays_; }

 private:
  BarrierRayGenerator rays_;
  Transform worldFromDisplay_;
  float affine_[3][4];  // worldFromDisplay_ as a plain affine matrix for the hot loop
};

// An off-axis pinhole camera at `eyeMm` (display frame) whose film is the front layer's
// rectangle: the picture an ideal window would show that eye (from virtualEye(eyeMm) when the
// design has a virtual gap: the picture the display means to show that eye). With `horizontalOnly`,
// the vertical perspective is the display's instead of the eye's: every ray meets the view line y =
// y_e, z = D in y (one-axis perspective, what a slit display can show; section 2.2).
class WindowCamera final : public Camera {
 public:
  WindowCamera(const Vec3d& eyeMm, const DisplayDesign& design, const DisplayPlacement& placement,
               int width, int height, bool horizontalOnly = false);

  int width() const override { return width_; }
  int height() const override { return height_; }
  Ray generateRay(const FilmSample& sample) const override;
  // The film as a pinhole grid (the benchmark's limit rays); the eye's own perspective, so
  // only for a camera without `horizontalOnly`.
  PinholeGrid grid(int samplesPerPixel) const {
    return {eye_, corner_, stepX_, stepY_, width_, height_, samplesPerPixel};
  }

 private:
  Vec3f eye_, corner_, stepX_, stepY_;
  int width_, height_;
  bool horizontalOnly_;
  Vec3f worldUp_;                   // display +y in the scene (scaled)
  float eyeZ_ = 0, eyeHeight_ = 0;  // the eye's z and y (mm)
  float frontHalfHeight_ = 0, viewLineY_ = 0, viewDistance_ = 0;  // mm
};

}  // namespace parallax
