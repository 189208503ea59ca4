#include "parallax/sim/crosstalk.h"

#include <algorithm>
#include <cmath>

#include "parallax/image/metrics.h"

namespace parallax {

namespace {

DisplayDesign pixelMode(const DisplayDesign& design) {
  DisplayDesign d = design;
  d.spec.subpixelRays = false;
  return d;
}

}  // namespace

Image viewCodedImage(const DisplayDesign& design, int view) {
  const BarrierRayGenerator rays(pixelMode(design));
  const Panel& panel = design.spec.imagePanel;
  Image image(panel.width, panel.height);
  for (int y = 0; y < panel.height; ++y)
    for (int x = 0; x < panel.width; ++x)
      if (rays.viewIndex(x, y) == view) image.at(x, y) = Vec3f(1.0f);
  return image;
}

Vec3d designEyePosition(const DisplayDesign& design, int view) {
  DisplayDesign pixels = design;  // view-coded layers are in pixel mode
  pixels.spec.subpixelRays = false;
  return BarrierRayGenerator(pixels).viewPosition(view);
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
