#include "parallax/display/depth_scaled_display.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace parallax {

double lensWindowSubpixels(const LensOptics& optics) {
  return std::max(1.0, optics.spotWidthSubpixels);
}

double lensDepthOfFieldMm(const LenticularDesign& design, double lenses) {
  const double windowSubpixels = lensWindowSubpixels(design.optics);
  const double halfCone = 0.5 * design.calibration.viewConeDegrees * 3.14159265358979323846 / 180;
  return lenses * design.horizontalLensPitchMm * design.subpixelsPerLens /
         (windowSubpixels * 2 * std::tan(halfCone));
}

namespace {

class DepthScaledDisplay final : public DisplayModel {
 public:
  DepthScaledDisplay(std::unique_ptr<DisplayModel> owned, const DisplayModel& inner, double k)
      : owned_(std::move(owned)), inner_(&inner), k_(k) {}

  DisplayKind kind() const override { return inner_->kind(); }
  const std::string& source() const override { return inner_->source(); }
  DisplayWindow window() const override { return inner_->window(); }
  FilmLayout film() const override { return inner_->film(); }
  int channelOfColumn(int column) const override { return inner_->channelOfColumn(column); }

  DisplayRay ray(double filmX, double filmY, double u, double v) const override {
    DisplayRay r = inner_->ray(filmX, filmY, u, v);
    scale(r.origin.x, r.origin.z, r.direction.x, r.direction.z);
    return r;
  }
  void rays16(const float filmX[16], const float filmY[16], const float u[16], const float v[16],
              double origin[3][16], double direction[3][16]) const override {
    inner_->rays16(filmX, filmY, u, v, origin, direction);
    for (int i = 0; i < 16; ++i)
      scale(origin[0][i], origin[2][i], direction[0][i], direction[2][i]);
  }
  bool centralRayOnly() const override { return inner_->centralRayOnly(); }
  bool columnFans() const override { return inner_->columnFans(); }
  int viewCount() const override { return inner_->viewCount(); }
  int viewIndex(int column, int row) const override { return inner_->viewIndex(column, row); }
  Vec3d viewPosition(int view) const override { return inner_->viewPosition(view); }
  double viewZoneWidthMm() const override { return inner_->viewZoneWidthMm(); }
  Vec3d eyeAcrossZone(double t) const override { return inner_->eyeAcrossZone(t); }
  bool horizontalParallaxOnly() const override { return inner_->horizontalParallaxOnly(); }
  Vec3d intendedEye(const Vec3d& eyeMm) const override {
    const Vec3d e = inner_->intendedEye(eyeMm);
    return {e.x, e.y, e.z / k_};
  }
  bool hasMaskLayer() const override { return inner_->hasMaskLayer(); }
  Image maskLayer() const override { return inner_->maskLayer(); }
  std::vector<DesignFigure> designReport() const override { return inner_->designReport(); }
  PanelSize viewerPanel() const override { return inner_->viewerPanel(); }
  double diffuserSigmaMm() const override { return inner_->diffuserSigmaMm(); }
  QuiltShape defaultQuilt() const override { return inner_->defaultQuilt(); }
  PanelSize quiltTile(int columns, int rows) const override {
    return inner_->quiltTile(columns, rows);
  }
  double directMappingViews() const override { return inner_->directMappingViews(); }
  std::string deviceNote() const override { return inner_->deviceNote(); }
  int denseViewCount() const override { return inner_->denseViewCount(); }
  Vec3d denseEye(int view, double inView, double distance) const override {
    return inner_->denseEye(view, inView, distance);
  }
  std::vector<Vec3d> denseDesignEyes() const override { return inner_->denseDesignEyes(); }
  std::string summaryClause() const override { return inner_->summaryClause(); }
  const DisplayDesign* barrierDesign() const override { return inner_->barrierDesign(); }
  const LenticularDesign* lenticularDesign() const override { return inner_->lenticularDesign(); }

 private:
  // The ray keeps the point where it meets the panel (z = 0) and its distance along z from its
  // origin; its horizontal slope dx/dz is scaled by k.
  void scale(double& originX, double originZ, double& directionX, double directionZ) const {
    const double t = -originZ / directionZ;  // origin + t direction lies on the panel
    const double panelX = originX + t * directionX;
    directionX *= k_;
    originX = panelX - t * directionX;
  }

  std::unique_ptr<DisplayModel> owned_;  // null when it views a display owned elsewhere
  const DisplayModel* inner_;
  double k_;
};

}  // namespace

namespace {

void checkScale(double depthScale) {
  if (!(depthScale > 0 && depthScale <= 1))
    throw std::invalid_argument("the depth scale must lie in (0, 1]");
}

}  // namespace

std::unique_ptr<DisplayModel> scaleDisplayedDepth(std::unique_ptr<DisplayModel> display,
                                                  double depthScale) {
  checkScale(depthScale);
  if (depthScale == 1) return display;
  const DisplayModel& inner = *display;
  return std::make_unique<DepthScaledDisplay>(std::move(display), inner, depthScale);
}

std::unique_ptr<DisplayModel> depthScaledView(const DisplayModel& display, double depthScale) {
  checkScale(depthScale);
  return std::make_unique<DepthScaledDisplay>(nullptr, display, depthScale);
}

}  // namespace parallax
