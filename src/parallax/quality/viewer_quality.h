// What viewers see, measured: the simulated display against the ideal view at dense eye
// positions across the view zone (docs/simulator.md, "The dense measure"). One ray per pixel is
// exact at the design eyes by construction, so a measure taken only there cannot tell a good
// prefilter from none; K eyes inside every view's window, at several distances, can.
#pragma once

#include <functional>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/display/display.h"
#include "parallax/display/display_model.h"
#include "parallax/image/image.h"
#include "parallax/scene/scene.h"
#include "parallax/sim/simulated_display.h"

namespace parallax {

struct DenseEye {
  Vec3d position;          // display mm
  double distance = 1.0;   // in units of the design distance D
  int view = 0;            // the view whose window holds the eye (at D; the same angle elsewhere)
  bool designEye = false;  // one of the views' design eyes (DisplayModel::viewPosition)
};

// K eyes evenly inside every view's window across the zone, at each distance f D: at D the
// view windows are S / views wide and eye k of view v sits at
//   x = e_c - S/2 + (v + (k + 1/2) / K) S / views,
// at f D the same angles from the view-zone centre's line (x scaled by f), so a farther row
// crosses the same views. Rows are ordered by distance, then left to right (a sweep).
std::vector<DenseEye> denseEyes(const DisplayDesign& design, int eyesPerView,
                                const std::vector<double>& distances);
// Any display: the same for a barrier; for other kinds K eyes inside each of its viewCount()
// windows across the zone (DisplayModel::eyeAcrossZone), at f D scaled from the zone's centre.
std::vector<DenseEye> denseEyes(const DisplayModel& display, int eyesPerView,
                                const std::vector<double>& distances);
// The design eyes of every view, at D (where one ray per pixel is exact).
std::vector<DenseEye> designEyes(const DisplayDesign& design);
std::vector<DenseEye> designEyes(const DisplayModel& display);

// The jitter seed of the truth's ideal views (RenderSettings::seed): one no render draws from
// (renders default to seed 0; the layer solvers' training eyes to trainingEyeSeed, layers/).
// A truth rendered with a render's own sample positions favours that render: with seed 0 the
// dense measure scored seed-0 renders about 0.02 dB and 0.002 SSIM higher than the same
// renders judged against independent samples (the slits' 1080p render 29.34 dB / 0.9508
// against 29.31 / 0.9480; docs/simulator.md, "The dense measure").
inline constexpr uint64_t kTruthJitterSeed = 0x7275746830f1e1d5ull;

// The ideal view from one eye through the display's window (one-axis perspective for
// horizontal-parallax displays), at the display's spatial resolution (`seen`'s): the truth the
// display is judged against. `bounces`: as the render's (RenderSettings::bounces), so that a
// path-traced render is judged against path-traced truth. `seed`: the samples' jitter.
Image idealView(const Scene& scene, const Accelerator& accelerator, const DisplayModel& display,
                const SimulatedDisplay& seen, const Vec3d& eyeMm, int width, int height,
                int samplesPerPixel, int threads, int bounces = 0,
                uint64_t seed = kTruthJitterSeed);
Image idealView(const Scene& scene, const Accelerator& accelerator, const DisplayDesign& design,
                const Vec3d& eyeMm, int width, int height, int samplesPerPixel, int threads,
                int bounces = 0, uint64_t seed = kTruthJitterSeed);

struct EyeQuality {
  DenseEye eye;
  double psnr = 0, ssim = 0;
  // How far the change from the previous eye of the row departs from the ideal's change:
  // RMS over pixels and channels of (S_i - S_{i-1}) - (R_i - R_{i-1}) in sRGB [0, 1] values,
  // S simulated, R ideal. Angular aliasing (popping, ghosts) while the viewer moves raises it.
  // Not a number for the first eye of a row.
  double flicker = 0;
  // The simulated view's mean luminance (linear, as the simulator normalised it).
  double meanLuminance = 0;
};

struct QualitySummary {
  int eyes = 0;
  double meanPsnr = 0, meanSsim = 0;
  double worstPsnr = 0;  // the lowest per-eye PSNR (as the ICME 2018 light-field challenge)
  Vec3d worstEye;
  double meanFlicker = 0;    // over the eyes that have one
  double meanLuminance = 0;  // of the simulated views
};

struct ViewerQuality {
  std::vector<EyeQuality> eyes;
  QualitySummary all;
  QualitySummary designOnly;  // the design eyes among `eyes` (biased: exact by construction)
  std::vector<std::pair<double, QualitySummary>> byDistance;
};

// Samples per pixel of the ideal views (simulate --reference-spp). The comparisons see them
// through the display's resolution, a box one aperture period wide (about nine pixels on the
// built-in display), so four stratified samples suffice: at the built-in 1080p display the
// dense measure's per-eye PSNR against 4-spp ideal views is within 0.008 dB of that against
// 64-spp ones (16 spp: 0.005 dB; 1 spp, the pixel centres: 0.63 dB lower), docs/simulator.md.
inline constexpr int kDefaultReferenceSpp = 4;

struct ViewerQualityOptions {
  int referenceSamplesPerPixel = kDefaultReferenceSpp;
  int threads = 0;
  int bounces = 0;  // of the ideal views: the render's --bounces
};

// Scores the simulated views of `simulator` at `eyes` against the ideal views of `scene`,
// one eye at a time (memory: a few images, whatever the eye count). `progress(done, total)`.
ViewerQuality measureViewerQuality(const Scene& scene, const Accelerator& accelerator,
                                   const DisplayModel& display, const SimulatedDisplay& simulator,
                                   const std::vector<DenseEye>& eyes,
                                   const ViewerQualityOptions& options,
                                   const std::function<void(int, int)>& progress = {});
// The same for several renders of one scene on one display (filters, sample counts, ...),
// sharing each eye's ideal view: one result per simulator, in order.
std::vector<ViewerQuality> measureViewerQuality(
    const Scene& scene, const Accelerator& accelerator, const DisplayModel& display,
    const std::vector<const SimulatedDisplay*>& simulators, const std::vector<DenseEye>& eyes,
    const ViewerQualityOptions& options, const std::function<void(int, int)>& progress = {});

// The summary of a set of per-eye scores.
QualitySummary summarise(const std::vector<EyeQuality>& eyes);

// The flicker figure between two consecutive eyes (see EyeQuality::flicker).
double flickerBetween(const Image& simulatedBefore, const Image& idealBefore,
                      const Image& simulated, const Image& ideal);

}  // namespace parallax
