#include "parallax/sim/crosstalk.h"

#include <algorithm>
#include <cmath>

#include "parallax/display/display_model.h"
#include "parallax/image/metrics.h"

namespace parallax {

namespace {

// The panel's pixel views: the display traced one ray per pixel, whatever the camera's choices.
std::unique_ptr<DisplayModel> pixelViews(const DisplayDesign& design) {
  return makeBarrierDisplay(designDisplay(design.spec));
}

}  // namespace

Image viewCodedImage(const DisplayDesign& design, int view) {
  const std::unique_ptr<DisplayModel> display = pixelViews(design);
  const Panel& panel = design.spec.imagePanel;
  Image image(panel.width, panel.height);
  for (int y = 0; y < panel.height; ++y)
    for (int x = 0; x < panel.width; ++x)
      if (display->viewIndex(x, y) == view) image.at(x, y) = Vec3f(1.0f);
  return image;
}

Vec3d designEyePosition(const DisplayDesign& design, int view) {
  return pixelViews(design)->viewPosition(view);  // view-coded layers are in pixel mode
}

CrosstalkResult measureCrosstalk(const DisplayDesign& design, const Image& maskLayer,
                                 const SimulationOptions& options, const Vec3d& eye) {
  CrosstalkResult result;
  const int views = pixelViewCount(design);
  for (int v = 0; v < views; ++v) {
    const DisplaySimulator sim(design, {viewCodedImage(design, v), maskLayer}, options);
    result.lightPerView.push_back(meanLuminance(sim.view(eye)));
  }
  const auto& light = result.lightPerView;
  result.ownView = int(std::max_element(light.begin(), light.end()) - light.begin());
  for (double l : light) result.brightness += l;
  result.crosstalk =
      result.brightness > 0 ? 1.0 - light[size_t(result.ownView)] / result.brightness : 0.0;
  return result;
}

}  // namespace parallax
