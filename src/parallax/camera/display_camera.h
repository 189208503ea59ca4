// Cameras tied to the display, for every kind of display (display/display_model.h): the display
// camera that renders the panel's film, and the ideal off-axis view through the display's
// window from one eye (`view --display-eye`).
#pragma once

#include <memory>

#include "parallax/camera/camera.h"
#include "parallax/core/transform.h"
#include "parallax/display/display_model.h"
#include "parallax/scene/scene.h"

namespace parallax {

// The placement's width for this window: placement.width, unless placement.fit is set; then
// the smallest width (the largest picture) at which every corner of the fit bounds, seen from
// the eye, falls inside the window with a 5 % margin on each side. Content pops out toward the
// eye, so this also keeps the near half of a deep object from filling the view.
float fitDisplayWidth(const DisplayPlacement& placement, const DisplayWindow& window);

// Display millimetres (docs/display-geometry.md) to scene units: the front layer's centre goes
// to placement.center, x to right = up x normal, y to up, z to normal, and the front layer's
// width in mm to fitDisplayWidth() scene units.
Transform worldFromDisplay(const DisplayPlacement& placement, const DisplayWindow& window);

// One ray per film sample of the display (a panel pixel, or one colour channel of it), as the
// display model says, carried from display millimetres into the scene by the placement.
class DisplayCamera final : public Camera {
 public:
  // `display` must outlive the camera.
  DisplayCamera(const DisplayModel& display, const DisplayPlacement& placement);
  // A barrier design: the camera owns its display model.
  DisplayCamera(const DisplayDesign& design, const DisplayPlacement& placement,
                const ViewFilter& filter = {})
      : DisplayCamera(makeBarrierDisplay(design, filter), placement) {}
  // A display model the camera owns.
  DisplayCamera(std::unique_ptr<DisplayModel> display, const DisplayPlacement& placement);

  int width() const override { return film_.columns; }
  int height() const override { return film_.rows; }
  Ray generateRay(const FilmSample& sample) const override;
  void generateRays16(const FilmSamples16& samples, RayPacket16& out) const override;
  PacketShape packetShape() const override;

  const DisplayModel& display() const { return *display_; }

 private:
  std::unique_ptr<DisplayModel> owned_;
  const DisplayModel* display_;
  FilmLayout film_;
  Transform worldFromDisplay_;
  float affine_[3][4];  // worldFromDisplay_ as a plain affine matrix for the hot loop
};

// An off-axis pinhole camera at `eyeMm` (display frame) whose film is the front layer's
// rectangle: the picture an ideal window would show that eye (from virtualEye(eyeMm) when the
// design has a virtual gap: the picture the display means to show that eye). With `horizontalOnly`,
// the vertical perspective is the display's instead of the eye's: every ray meets the view line y =
// y_e, z = D in y (one-axis perspective, what a slit display can show; section 2.2).
// WindowCamera's ray formulas' constants, made once (generateRays16 reads them in place).
struct WindowRayParameters {
  Vec3f eye, corner, stepX, stepY, up;  // up: display +y in the scene (scaled)
  float frontHalfHeight = 0, rowStepMm = 0, viewLineY = 0, eyeHeight = 0;  // mm
  float depthRatio = 0;  // the eye's z over the view distance
  bool horizontalOnly = false;
};

class WindowCamera final : public Camera {
 public:
  WindowCamera(const Vec3d& eyeMm, const DisplayModel& display, const DisplayPlacement& placement,
               int width, int height, bool horizontalOnly = false);
  WindowCamera(const Vec3d& eyeMm, const DisplayDesign& design, const DisplayPlacement& placement,
               int width, int height, bool horizontalOnly = false)
      : WindowCamera(eyeMm, *makeBarrierDisplay(design), placement, width, height, horizontalOnly) {
  }

  int width() const override { return width_; }
  int height() const override { return height_; }
  Ray generateRay(const FilmSample& sample) const override;
  void generateRays16(const FilmSamples16& samples, RayPacket16& out) const override;
  // The film as a pinhole grid (the benchmark's limit rays); the eye's own perspective, so
  // only for a camera without `horizontalOnly`.
  PinholeGrid grid(int samplesPerPixel) const {
    return {p_.eye, p_.corner, p_.stepX, p_.stepY, width_, height_, samplesPerPixel};
  }

 private:
  int width_, height_;
  WindowRayParameters p_;
};

}  // namespace parallax
