// The parallax barrier as a DisplayModel: the image layer's film through its apertures
// (barrier_rays.h), the mask as its second layer.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "parallax/display/barrier_rays.h"
#include "parallax/display/display_model.h"
#include "parallax/display/mask.h"

namespace parallax {

namespace {

class BarrierDisplay final : public DisplayModel {
 public:
  BarrierDisplay(const DisplayDesign& design, const ViewFilter& filter)
      : design_(design),
        rays_(design, filter),
        centralRayOnly_(filter.kind == ViewFilterKind::None) {}

  DisplayKind kind() const override { return DisplayKind::Barrier; }
  const std::string& source() const override { return design_.spec.source; }
  DisplayWindow window() const override { return displayWindow(design_); }
  FilmLayout film() const override {
    const Panel& p = design_.spec.imagePanel;
    return {rays_.filmWidth(), rays_.filmHeight(), p.width, p.height, rays_.subpixelMode()};
  }
  int channelOfColumn(int column) const override { return rays_.channelOfColumn(column); }
  DisplayRay ray(double filmX, double filmY, double u, double v) const override {
    const BarrierRay r = rays_.ray(filmX, filmY, u, v);
    return {r.origin, r.direction};
  }
  void rays16(const float filmX[16], const float filmY[16], const float u[16], const float v[16],
              double origin[3][16], double direction[3][16]) const override {
    rays_.rays16(filmX, filmY, u, v, origin, direction);
  }
  bool centralRayOnly() const override { return centralRayOnly_; }
  bool columnFans() const override { return true; }
  int viewCount() const override { return interleavedViewCount(design_); }
  int viewIndex(int column, int row) const override { return rays_.viewIndex(column, row); }
  Vec3d viewPosition(int view) const override { return rays_.viewPosition(view); }
  double viewZoneWidthMm() const override { return design_.viewZoneWidthMm; }
  Vec3d eyeAcrossZone(double t) const override {
    return {design_.spec.viewZoneCenterXMm + design_.viewZoneWidthMm * (t - 0.5),
            design_.spec.viewZoneHeightMm, design_.viewDistanceMm};
  }
  bool horizontalParallaxOnly() const override { return !rays_.mask().isPinholeGrid(); }
  Vec3d intendedEye(const Vec3d& eyeMm) const override { return virtualEye(design_, eyeMm); }
  bool hasMaskLayer() const override { return true; }
  Image maskLayer() const override { return maskLayerImage(design_); }
  std::vector<DesignFigure> designReport() const override {
    const DisplayDesign& d = design_;
    return {{"views", d.views, ""},
            {"gap", d.gapMm, "mm"},
            {"view_distance", d.viewDistanceMm, "mm"},
            {"view_zone_width", d.viewZoneWidthMm, "mm"},
            {"view_width", d.viewWidthMm, "mm"},
            {"screen_period", d.screenPeriodPx, "px"},
            {"slit_period", d.slitPeriodPx, "px"},
            {"depth_of_field", d.depthOfFieldMm, "mm"},
            {"virtual_gap", d.virtualGapMm, "mm"},
            {"virtual_distance", d.virtualDistanceMm, "mm"}};
  }
  PanelSize viewerPanel() const override {
    const DisplaySpec& spec = design_.spec;
    const Panel& front = spec.order == LayerOrder::BarrierBack ? spec.imagePanel : spec.maskPanel;
    return {front.width, front.height};
  }
  double diffuserSigmaMm() const override { return design_.spec.diffuserSigmaMm; }
  double directMappingViews() const override {
    return std::max(1.0, std::round(design_.screenPeriodPx));
  }
  int denseViewCount() const override { return pixelViewCount(design_); }
  Vec3d denseEye(int view, double inView, double distance) const override {
    const int views = pixelViewCount(design_);
    const double centre = design_.spec.viewZoneCenterXMm, y = design_.spec.viewZoneHeightMm;
    const double zone = design_.viewZoneWidthMm, window = zone / views;
    const double x = -0.5 * zone + (view + inView) * window;
    return {centre + x * distance, y, design_.viewDistanceMm * distance};
  }
  // The panel's pixel views (the default camera's), as the dense eyes count them.
  std::vector<Vec3d> denseDesignEyes() const override {
    const std::unique_ptr<DisplayModel> pixels = makeBarrierDisplay(designDisplay(design_.spec));
    std::vector<Vec3d> eyes;
    for (int v = 0; v < pixelViewCount(design_); ++v) eyes.push_back(pixels->viewPosition(v));
    return eyes;
  }
  const DisplayDesign* barrierDesign() const override { return &design_; }

 private:
  DisplayDesign design_;
  BarrierRayGenerator rays_;
  bool centralRayOnly_;
};

}  // namespace

const char* displayKindName(DisplayKind kind) {
  switch (kind) {
    case DisplayKind::Barrier:
      return "barrier";
    case DisplayKind::Lenticular:
      return "lenticular";
    case DisplayKind::Other:
      break;
  }
  return "other";
}

void DisplayModel::rays16(const float filmX[16], const float filmY[16], const float u[16],
                          const float v[16], double origin[3][16], double direction[3][16]) const {
  for (int i = 0; i < 16; ++i) {
    const DisplayRay r = ray(filmX[i], filmY[i], u[i], v[i]);
    origin[0][i] = r.origin.x, origin[1][i] = r.origin.y, origin[2][i] = r.origin.z;
    direction[0][i] = r.direction.x, direction[1][i] = r.direction.y;
    direction[2][i] = r.direction.z;
  }
}

std::unique_ptr<DisplayModel> makeBarrierDisplay(const DisplayDesign& design,
                                                 const ViewFilter& filter) {
  return std::make_unique<BarrierDisplay>(design, filter);
}

DisplayWindow displayWindow(const DisplayDesign& design) {
  return {design.frontWidthMm(),
          design.frontHeightMm(),
          {design.spec.viewZoneCenterXMm, design.spec.viewZoneHeightMm, design.viewDistanceMm}};
}

Vec3d virtualEye(const DisplayDesign& d, const Vec3d& eyeMm) {
  const double g = d.gapMm, gv = d.virtualGapMm, distance = d.viewDistanceMm;
  if (gv == g || d.virtualDistanceMm != distance || !(eyeMm.z > 0)) return eyeMm;
  const double r = d.spec.order == LayerOrder::BarrierBack
                       ? g * (gv + distance) / (gv * (g + distance))
                       : g / gv;
  const double z = eyeMm.z * distance / (r * (distance - eyeMm.z) + eyeMm.z);
  const double centre = d.spec.viewZoneCenterXMm;
  return {centre + r * (eyeMm.x - centre) * z / eyeMm.z, eyeMm.y, z};
}

Image maskLayerImage(const DisplayDesign& design) {
  const Panel& panel = design.spec.maskPanel;
  const std::vector<float> coverage = MaskGeometry(design).rasterize();
  Image image(panel.width, panel.height);
  for (size_t i = 0; i < coverage.size(); ++i) image.pixels()[i] = Vec3f(coverage[i]);
  return image;
}

}  // namespace parallax
