// The training eyes of the layer solvers: dense eyes across the view zone (quality/), each with
// the ideal view it should see, ray-traced through the display's window and brought to the
// display's resolution as the dense measure does, times the brightness the layers aim at.
#pragma once

#include <functional>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/display/display.h"
#include "parallax/layers/layer_solver.h"
#include "parallax/scene/scene.h"

namespace parallax {

struct TrainingOptions {
  // K eyes inside every view's window at each distance (units of D). The defaults sit between
  // the dense measure's own eyes (K = 4 at 0.8, 1, 1.25 D), which stay unseen by the solver.
  int eyesPerView = 2;
  std::vector<double> distances{0.8, 1.0, 1.25};
  int referenceSamplesPerPixel = 4;
  int bounces = 0;  // of the ideal views: the render's --bounces
  // Targets are the ideal views times targetScale: the slit mask's mean transmittance for the
  // slits' own brightness, times a gain for brighter layers.
  double targetScale = 1.0;
  // The image layer's errors on sRGB values (TrainingView::encodingScale) instead of in linear
  // light: measured better in mean PSNR, SSIM, worst eye and flicker (docs/content-adaptive.md).
  bool srgbWeights = false;
  int threads = 0;
};

// Bytes the training views hold (one target per eye at the front layer's resolution: floats,
// or 16 bits per channel for sRGB errors), for the caller's memory check before building them.
double trainingBytes(const DisplayDesign& design, const TrainingOptions& options);
// Bytes optimizeImageLayer holds besides for a grey mask: each training eye's view of the mask,
// one float per pixel (layer_solver.cpp, ImageLayerPasses).
double seenMaskBytes(const DisplayDesign& design, const TrainingOptions& options);

std::vector<TrainingView> trainingViews(const Scene& scene, const Accelerator& accelerator,
                                        const DisplayDesign& design, const TrainingOptions& options,
                                        const std::function<void(int, int)>& progress = {});

// The mean transmittance of a layer (over pixels and channels).
double meanTransmittance(const Image& layer);

}  // namespace parallax
