#include "parallax/render/display_render.h"

#include "parallax/camera/display_camera.h"
#include "parallax/display/mask.h"
#include "parallax/sim/simulator.h"  // maskLayerImage

#include <algorithm>
#include <cmath>

namespace parallax {

DisplayLayers renderDisplay(const Scene& scene, const Accelerator& accelerator,
                            const DisplayDesign& design, const RenderSettings& settings,
                            const ProgressCallback& progress, const ViewFilter& filter) {
  const DisplayCamera camera(design, scene.display, filter);
  DisplayLayers layers;
  Image film = render(scene, accelerator, camera, settings, &layers.stats, progress);
  const BarrierRayGenerator& rays = camera.rays();
  if (!rays.subpixelMode()) {
    layers.image = std::move(film);
  } else {
    layers.image =
        panelFromSubpixelFilm(film, [&rays](int column) { return rays.channelOfColumn(column); });
  }
  layers.mask = maskLayerImage(design);
  return layers;
}

Image interleaveViews(const DisplayDesign& design, const std::vector<Image>& views) {
  const BarrierRayGenerator rays(design);
  const Panel& panel = design.spec.imagePanel;
  Image image(panel.width, panel.height);
  for (int y = 0; y < panel.height; ++y)
    for (int column = 0; column < rays.filmWidth(); ++column) {
      const int view = rays.viewIndex(column, y);
      const Image& source = views.at(size_t(view));
      if (!rays.subpixelMode()) {
        image.at(column, y) = source.at(column, y);
      } else {
        const int channel = rays.channelOfColumn(column);
        image.at(column / 3, y)[channel] = source.at(column / 3, y)[channel];
      }
    }
  return image;
}

DisplayLayers renderDirectMapping(const Scene& scene, const Accelerator& accelerator,
                                  const DisplayDesign& design, const RenderSettings& settings,
                                  const ProgressCallback& progress) {
  const BarrierRayGenerator rays(design);
  const Panel& panel = design.spec.imagePanel;
  const double columnsPerGroup = design.screenPeriodPx * (rays.subpixelMode() ? 3.0 : 1.0);
  const int viewCount = std::max(1, int(std::lround(columnsPerGroup)));
  const bool horizontalOnly = !rays.mask().isPinholeGrid();
  DisplayLayers layers;
  std::vector<Image> views;
  for (int view = 0; view < viewCount; ++view) {
    const WindowCamera camera(rays.viewPosition(view), design, scene.display, panel.width,
                              panel.height, horizontalOnly);
    RenderStats stats;
    views.push_back(render(scene, accelerator, camera, settings, &stats, [&](int done, int total) {
      if (progress) progress(view * total + done, viewCount * total);
    }));
    layers.stats.cameraRays += stats.cameraRays;
    layers.stats.shadowRays += stats.shadowRays;
    layers.stats.secondaryRays += stats.secondaryRays;
    layers.stats.seconds += stats.seconds;
  }
  layers.image = interleaveViews(design, views);
  layers.mask = maskLayerImage(design);
  return layers;
}

}  // namespace parallax
