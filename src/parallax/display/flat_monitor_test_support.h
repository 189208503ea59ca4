// Shared by the tests: a third display kind with no file, made in code (DisplayKind::Other).
#pragma once

#include <string>
#include <vector>

#include "parallax/display/display_model.h"

namespace parallax {

// A third kind, made in the tests alone: a flat monitor whose every pixel is seen from one eye,
// its rays from the eye through the pixels' centres on the window. The display camera and the
// display render take it as they take the two kinds with files, and its picture is then the
// window camera's from that eye (a second code path: camera/display_camera.h, WindowCamera).
// The jobs runners take it made in code (jobs::DisplayRequest::madeInCode).
class FlatMonitor final : public DisplayModel {
 public:
  FlatMonitor(int width, int height, double widthMm, const Vec3d& eye)
      : width_(width), height_(height), widthMm_(widthMm), eye_(eye) {}
  DisplayKind kind() const override { return DisplayKind::Other; }
  const std::string& source() const override { return source_; }
  DisplayWindow window() const override { return {widthMm_, heightMm(), eye_}; }
  FilmLayout film() const override { return {width_, height_, width_, height_, false}; }
  int channelOfColumn(int) const override { return 0; }
  DisplayRay ray(double filmX, double filmY, double, double) const override {
    const double x = (filmX / width_ - 0.5) * widthMm_, y = (0.5 - filmY / height_) * heightMm();
    const double k = 1.0 / eye_.z;  // direction.z = -1
    return {eye_, {(x - eye_.x) * k, (y - eye_.y) * k, -1.0}};
  }
  bool centralRayOnly() const override { return true; }
  bool columnFans() const override { return false; }
  int viewCount() const override { return 1; }
  int viewIndex(int, int) const override { return 0; }
  Vec3d viewPosition(int) const override { return eye_; }
  double viewZoneWidthMm() const override { return 0.0; }
  Vec3d eyeAcrossZone(double) const override { return eye_; }
  bool horizontalParallaxOnly() const override { return false; }
  std::vector<DesignFigure> designReport() const override { return {{"width_mm", widthMm_, "mm"}}; }

 private:
  double heightMm() const { return widthMm_ * height_ / width_; }
  int width_, height_;
  double widthMm_;
  Vec3d eye_;
  std::string source_ = "<flat monitor>";
};

}  // namespace parallax
