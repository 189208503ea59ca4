// The training eyes of the layer solvers: dense eyes across the view zone (quality/), each with
// the ideal view it should see, ray-traced through the display's window and brought to the
// display's resolution as the dense measure does, times the brightness the layers aim at.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/display/display.h"
#include "parallax/layers/layer_method.h"
#include "parallax/layers/layer_problem.h"
#include "parallax/scene/scene.h"

namespace parallax {

inline constexpr int kDefaultTrainingSpp = 2;

// Training eye `eye`'s jitter seed (RenderSettings::seed) for a render of seed `renderSeed`: a
// SplitMix64 step of the two, so that no two eyes, and no eye and the render itself or the
// truth's ideal views (kTruthJitterSeed, quality/), share their sample positions.
uint64_t trainingEyeSeed(uint64_t renderSeed, size_t eye);

struct TrainingOptions {
  // K eyes inside every view's window at each distance (units of D). The defaults sit between
  // the dense measure's own eyes (K = 4 at 0.8, 1, 1.25 D), which stay unseen by the solver.
  int eyesPerView = 2;
  std::vector<double> distances{0.8, 1.0, 1.25};
  // Samples per pixel of the ideal views, each eye's jitter its own (trainingEyeSeed): the
  // solve then averages the targets' sampling errors over its eyes, and 2 spp solve as well as
  // 4 spp with one jitter for every eye did, in half the ideal views' time (docs/
  // content-adaptive.md, "The targets' samples").
  int referenceSamplesPerPixel = kDefaultTrainingSpp;
  uint64_t seed = 0;  // the render's --seed, from which each eye's jitter seed is drawn
  int bounces = 0;    // of the ideal views: the render's --bounces
  // Targets are the ideal views times targetScale: the slit mask's mean transmittance for the
  // slits' own brightness, times a gain for brighter layers.
  double targetScale = 1.0;
  // The image layer's errors on sRGB values (TrainingView::encodingScale) instead of in linear
  // light: measured better in mean PSNR, SSIM, worst eye and flicker (docs/content-adaptive.md).
  bool srgbWeights = false;
  // Targets kept as B^T t (TrainingView::encodeBoxedTarget), for factorizeLayers with the image
  // in front (linear light); the same bytes.
  bool boxedTargets = false;
  // The eyes see the layers through the panels' colour filters (SeenOptics::colourFilters).
  bool colourFilters = false;
  // With colourFilters and a diffuser: the rear layer is seen as its stripe cells blurred
  // (RearDiffuser::striped, SeenOptics::rearStripeCells).
  bool rearStripeCells = false;
  // Eyes with a pupil (SeenOptics::pupilDiameterMm, pupilSamples): each a pupil's sights.
  double pupilDiameterMm = 0;
  int pupilSamples = 16;
  int threads = 0;
};

// Bytes the training views hold (one target per eye at the front layer's resolution: floats,
// or 16 bits per channel for sRGB errors), for the caller's memory check before building them.
double trainingBytes(const DisplayDesign& design, const TrainingOptions& options);
// Bytes optimizeImageLayer holds besides for a grey mask: each training eye's view of the mask,
// one float per pixel (image_layer_solver.cpp, ImageLayerPasses; three through colour filters, for
// a band of rows).
double seenMaskBytes(const DisplayDesign& design, const TrainingOptions& options);

// Whether `method`'s solve makes its targets a band of rows at a time as it goes
// (optimizeImageLayerByBands): optimized-image with sRGB errors, the image in front and a box
// along rows only (slits; a pinhole mask's box spans rows too). Its targets then hold
// kTargetBandRows rows of every eye at a time instead of whole views.
bool solvesByBands(const DisplayDesign& design, const TrainingOptions& options, LayerMethod method);
// (kTargetBandRows: layer_problem.h.)
// Bytes `method`'s solve holds for its training eyes: their targets (trainingBytes) and, for
// optimized-image, the mask as they see it (seenMaskBytes), whole or a band's (solvesByBands);
// for the caller's memory check before building them.
double trainingHeldBytes(const DisplayDesign& design, const TrainingOptions& options,
                         LayerMethod method);

std::vector<TrainingView> trainingViews(const Scene& scene, const Accelerator& accelerator,
                                        const DisplayDesign& design, const TrainingOptions& options,
                                        const std::function<void(int, int)>& progress = {});

// The training eyes of trainingViews, in its order, without their targets (for
// optimizeImageLayerByBands, whose targets IdealViewBands makes).
std::vector<TrainingView> trainingEyes(const DisplayDesign& design, const TrainingOptions& options);

// trainingViews' targets a band of rows at a time (optimizeImageLayerByBands' BandTargets): each
// eye's ideal view rendered on the renderer's tiles of those rows only, through the display's box
// along rows, scaled and encoded as trainingViews makes them, so the same codes. Needs the image
// in front and a box along rows only (slits: solvesByBands, or nmf's boxed targets). One camera
// and tile renderer per eye, made once; eyes in parallel.
class IdealViewBands {
 public:
  IdealViewBands(const Scene& scene, const Accelerator& accelerator, const DisplayDesign& design,
                 const TrainingOptions& options);
  ~IdealViewBands();
  IdealViewBands(const IdealViewBands&) = delete;
  IdealViewBands& operator=(const IdealViewBands&) = delete;
  // `firstRow` a multiple of the renderer's tile rows (TileGrid::kRows).
  void operator()(int firstRow, int rows, std::vector<TrainingView>& views) const;
  // Every eye's whole target as boxed codes (TrainingView::encodeBoxedTarget), made a band of
  // kTargetBandRows rows at a time (trainingViews with boxedTargets); progress(bands done, bands).
  void wholeBoxedTargets(std::vector<TrainingView>& views,
                         const std::function<void(int, int)>& progress = {}) const;
  // Wall time spent in operator() and wholeBoxedTargets so far.
  double seconds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The mean transmittance of a layer (over pixels and channels).
double meanTransmittance(const Image& layer);

}  // namespace parallax
