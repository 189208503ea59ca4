#include "parallax/render/display_render.h"

#include "parallax/camera/display_camera.h"

namespace parallax {

RenderSettings displayRenderSettings(const DisplayModel& display, RenderSettings settings) {
  if (display.centralRayOnly()) settings.samplesPerPixel = 1;
  return settings;
}

DisplayLayers renderDisplay(const Scene& scene, const Accelerator& accelerator,
                            const DisplayModel& display, const RenderSettings& settings,
                            const ProgressCallback& progress) {
  const DisplayCamera camera(display, scene.display);
  DisplayLayers layers;
  Image film = render(scene, accelerator, camera, displayRenderSettings(display, settings),
                      &layers.stats, progress);
  if (!display.film().subpixelColumns) {
    layers.image = std::move(film);
  } else {
    layers.image = panelFromSubpixelFilm(
        film, [&display](int column) { return display.channelOfColumn(column); });
  }
  if (display.hasMaskLayer()) layers.mask = display.maskLayer();
  return layers;
}

DisplayLayers renderDisplay(const Scene& scene, const Accelerator& accelerator,
                            const DisplayDesign& design, const RenderSettings& settings,
                            const ProgressCallback& progress, const ViewFilter& filter) {
  return renderDisplay(scene, accelerator, *makeBarrierDisplay(design, filter), settings, progress);
}

Image interleaveViews(const DisplayModel& display, const std::vector<Image>& views) {
  const FilmLayout film = display.film();
  Image image(film.panelWidth, film.panelHeight);
  for (int y = 0; y < film.rows; ++y)
    for (int column = 0; column < film.columns; ++column) {
      const Image& source = views.at(size_t(display.viewIndex(column, y)));
      if (!film.subpixelColumns) {
        image.at(column, y) = source.at(column, y);
      } else {
        const int channel = display.channelOfColumn(column);
        image.at(column / 3, y)[channel] = source.at(column / 3, y)[channel];
      }
    }
  return image;
}

Image interleaveViews(const DisplayDesign& design, const std::vector<Image>& views) {
  return interleaveViews(*makeBarrierDisplay(design), views);
}

DisplayLayers renderDirectMapping(const Scene& scene, const Accelerator& accelerator,
                                  const DisplayModel& display, const RenderSettings& settings,
                                  const ProgressCallback& progress) {
  const FilmLayout film = display.film();
  const int viewCount = display.viewCount();
  DisplayLayers layers;
  std::vector<Image> views;
  for (int view = 0; view < viewCount; ++view) {
    const WindowCamera camera(display.viewPosition(view), display, scene.display, film.panelWidth,
                              film.panelHeight, display.horizontalParallaxOnly());
    RenderStats stats;
    views.push_back(render(scene, accelerator, camera, settings, &stats, [&](int done, int total) {
      if (progress) progress(view * total + done, viewCount * total);
    }));
    layers.stats += stats;
  }
  layers.image = interleaveViews(display, views);
  if (display.hasMaskLayer()) layers.mask = display.maskLayer();
  return layers;
}

DisplayLayers renderDirectMapping(const Scene& scene, const Accelerator& accelerator,
                                  const DisplayDesign& design, const RenderSettings& settings,
                                  const ProgressCallback& progress) {
  return renderDirectMapping(scene, accelerator, *makeBarrierDisplay(design), settings, progress);
}

}  // namespace parallax
