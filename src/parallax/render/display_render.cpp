#include "parallax/render/display_render.h"

#include "parallax/camera/display_camera.h"
#include "parallax/display/mask.h"

namespace parallax {

Image maskLayerImage(const DisplayDesign& design) {
  const Panel& panel = design.spec.maskPanel;
  const std::vector<float> coverage = MaskGeometry(design).rasterize();
  Image mask(panel.width, panel.height);
  for (size_t i = 0; i < coverage.size(); ++i) mask.pixels()[i] = Vec3f(coverage[i]);
  return mask;
}

DisplayLayers renderDisplay(const Scene& scene, const Accelerator& accelerator,
                            const DisplayDesign& design, const RenderSettings& settings,
                            const ProgressCallback& progress) {
  const DisplayCamera camera(design, scene.display);
  DisplayLayers layers;
  Image film = render(scene, accelerator, camera, settings, &layers.stats, progress);
  const BarrierRayGenerator& rays = camera.rays();
  if (!rays.subpixelMode()) {
    layers.image = std::move(film);
  } else {
    // Each subpixel column rendered its own ray; its channel keeps only its own colour.
    const Panel& panel = design.spec.imagePanel;
    layers.image = Image(panel.width, panel.height);
    for (int y = 0; y < panel.height; ++y)
      for (int column = 0; column < film.width(); ++column) {
        const int channel = rays.channelOfColumn(column);
        layers.image.at(column / 3, y)[channel] = film.at(column, y)[channel];
      }
  }
  layers.mask = maskLayerImage(design);
  return layers;
}

}  // namespace parallax
