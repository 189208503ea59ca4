// The render loop: tiles in parallel (oneTBB), 16-ray packets within a tile, deterministic
// per-sample random streams, shading in linear light.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/image/image.h"
#include "parallax/render/tile_packets.h"
#include "parallax/scene/scene.h"

namespace parallax {

struct RenderSettings {
  int samplesPerPixel = 1;  // a square n*n is stratified; 1 casts exactly the pixel centre
  uint64_t seed = 0;        // varies the jitter pattern; the same seed gives the same image
  int threads = 0;          // 0: all cores. The image does not depend on it.
  JitterSharing jitter = JitterSharing::Auto;  // tile_packets.h
  // Adaptive sampling: samplesPerPixel becomes a cap. A pixel's samples come in stratified
  // groups (PacketWalk's progressive order); after each group, a pixel whose estimate is
  // already certain stops: the standard error of its mean luminance, sRGB-encoded, below
  // `adaptiveThreshold` (in [0, 1] code values; 1/255 is one 8-bit step), estimated from the
  // spread of its group means once it has two groups (from its samples' spread after the
  // first), and the means of its neighbours in the packet within kNeighbourOverThreshold
  // thresholds of its own (docs/display-geometry.md, "Adaptive sampling"). Each pixel decides
  // on its own samples and its packet's only, so the image does not depend on the thread count.
  bool adaptive = false;
  double adaptiveThreshold = 2.0 / 255.0;
  static constexpr double kNeighbourOverThreshold = 2.0;
  // Diffuse bounces of path tracing with next-event estimation (docs/path-tracing.md): 0 is
  // direct light only (light reflected once, plus mirror chains and the ambient term); N
  // follows each path through up to N cosine-weighted diffuse bounces, so light reflected up
  // to N + 1 times reaches the camera.
  int bounces = 0;
  static constexpr int kMaxBounces = 64;
  // One part of a frame split across processes (docs/distributed.md): only the bands of
  // TileGrid::kRows film rows b with b % bandParts == bandPart are rendered; the other pixels
  // stay zero (all bits), so the parts of all processes merge by a bitwise OR. A pixel depends
  // only on its own packet (16 rows of one band), so the merged film equals one process's.
  // Interleaved bands balance the work: a frame's cost varies smoothly from top to bottom.
  int bandParts = 1, bandPart = 0;
  bool rendersBand(int band) const { return band % bandParts == bandPart; }
};

struct RenderStats {
  uint64_t cameraRays = 0;  // primary rays
  uint64_t shadowRays = 0;
  uint64_t secondaryRays = 0;  // mirror and diffuse bounces (closest-hit rays after the camera's)
  uint64_t bounceRays = 0;     // of which diffuse bounces (RenderSettings::bounces)
  uint64_t cameraMisses = 0;   // primary rays that met nothing (the background)
  double seconds = 0.0;

  uint64_t totalRays() const { return cameraRays + shadowRays + secondaryRays; }
  // Adds another render's rays and time (several views of one job).
  RenderStats& operator+=(const RenderStats& other) {
    cameraRays += other.cameraRays;
    shadowRays += other.shadowRays;
    secondaryRays += other.secondaryRays;
    bounceRays += other.bounceRays;
    cameraMisses += other.cameraMisses;
    seconds += other.seconds;
    return *this;
  }
};

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
