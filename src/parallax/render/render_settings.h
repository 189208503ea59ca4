// What a render is asked (RenderSettings: samples, seed, threads, jitter, adaptive sampling,
// bounces, a process's bands) and what it did (RenderStats: its rays and time): shared by the
// render loop (render.h) and the packet tracer it drives (packet_tracer.h).
#pragma once

#include <cstdint>

#include "parallax/render/tile_packets.h"

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
  // Gaussian splats (docs/splats.md): responses evaluated along camera rays (what a walk
  // costs) and Gaussians blended into them.
  uint64_t splatsEvaluated = 0;
  uint64_t splatsBlended = 0;
  double seconds = 0.0;

  uint64_t totalRays() const { return cameraRays + shadowRays + secondaryRays; }
  // Adds another render's rays and time (several views of one job).
  RenderStats& operator+=(const RenderStats& other) {
    cameraRays += other.cameraRays;
    shadowRays += other.shadowRays;
    secondaryRays += other.secondaryRays;
    bounceRays += other.bounceRays;
    cameraMisses += other.cameraMisses;
    splatsEvaluated += other.splatsEvaluated;
    splatsBlended += other.splatsBlended;
    seconds += other.seconds;
    return *this;
  }
};

}  // namespace parallax
