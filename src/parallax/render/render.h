// The render loop: tiles in parallel (oneTBB), 16-ray packets within a tile, deterministic
// per-sample random streams, shading in linear light.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/image/image.h"
#include "parallax/render/render_settings.h"
#include "parallax/scene/scene.h"

namespace parallax {

// Called from worker threads with the number of finished and total tiles.
using ProgressCallback = std::function<void(int done, int total)>;

// A subpixel film (three columns per panel pixel, one ray each) as the panel's picture: film
// column c is channel channelOfColumn(c) of pixel c / 3, and keeps only that channel's colour.
template <class ChannelOfColumn>
Image panelFromSubpixelFilm(const Image& film, ChannelOfColumn channelOfColumn) {
  Image panel(film.width() / 3, film.height());
  for (int y = 0; y < film.height(); ++y)
    for (int column = 0; column < 3 * panel.width(); ++column) {
      const int channel = channelOfColumn(column);
      panel.at(column / 3, y)[channel] = film.at(column, y)[channel];
    }
  return panel;
}

Image render(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
             const RenderSettings& settings, RenderStats* stats = nullptr,
             const ProgressCallback& progress = {});

// render()'s work one tile at a time, for callers that look at single tiles (the benchmark
// times Embree on exactly the rays a tile traces). Tiles write disjoint pixels of `image`
// (camera.width() x camera.height()), so different threads may render different tiles.
class TileRenderer {
 public:
  TileRenderer(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
               const RenderSettings& settings);
  ~TileRenderer();
  TileRenderer(const TileRenderer&) = delete;
  TileRenderer& operator=(const TileRenderer&) = delete;

  int tileCount() const;
  // The band (TileGrid::kRows film rows) a tile lies in.
  int tileBand(int tile) const;
  void renderTile(int tile, Image& image, RenderStats& stats) const;
  // The same into `image` holding only film rows [firstRow, firstRow + image.height()) (the
  // tile's rows among them): the same pixels as a whole film's rows (their random streams
  // depend on the film pixel only), for callers that go through a film band by band.
  void renderTile(int tile, Image& image, int firstRow, RenderStats& stats) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace parallax
