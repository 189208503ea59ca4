#include "parallax/quality/viewer_quality.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "parallax/camera/display_camera.h"
#include "parallax/core/parallel.h"
#include "parallax/display/display_model.h"
#include "parallax/image/metrics.h"
#include "parallax/render/render.h"

namespace parallax {

std::vector<DenseEye> denseEyes(const DisplayDesign& design, int eyesPerView,
                                const std::vector<double>& distances) {
  return denseEyes(*makeBarrierDisplay(design), eyesPerView, distances);
}

std::vector<DenseEye> designEyes(const DisplayDesign& design) {
  return designEyes(*makeBarrierDisplay(design));
}

std::vector<DenseEye> denseEyes(const DisplayModel& display, int eyesPerView,
                                const std::vector<double>& distances) {
  std::vector<DenseEye> eyes;
  const int views = display.denseViewCount();
  for (double f : distances)
    for (int v = 0; v < views; ++v)
      for (int k = 0; k < eyesPerView; ++k)
        eyes.push_back({display.denseEye(v, (k + 0.5) / eyesPerView, f), f, v, false});
  return eyes;
}

std::vector<DenseEye> designEyes(const DisplayModel& display) {
  std::vector<DenseEye> eyes;
  const std::vector<Vec3d> positions = display.denseDesignEyes();
  for (int v = 0; v < int(positions.size()); ++v)
    eyes.push_back({positions[size_t(v)], 1.0, v, true});
  return eyes;
}

Image idealView(const Scene& scene, const Accelerator& accelerator, const DisplayModel& display,
                const SimulatedDisplay& seen, const Vec3d& eye, int width, int height, int spp,
                int threads, int bounces, uint64_t seed) {
  const WindowCamera camera(eye, display, scene.display, width, height,
                            display.horizontalParallaxOnly());
  RenderSettings settings;
  settings.samplesPerPixel = spp;
  settings.threads = threads;
  settings.bounces = bounces;
  settings.seed = seed;
  return seen.atDisplayResolution(render(scene, accelerator, camera, settings));
}

Image idealView(const Scene& scene, const Accelerator& accelerator, const DisplayDesign& d,
                const Vec3d& eye, int width, int height, int spp, int threads, int bounces,
                uint64_t seed) {
  const std::unique_ptr<DisplayModel> display = makeBarrierDisplay(d);
  const WindowCamera camera(eye, *display, scene.display, width, height,
                            display->horizontalParallaxOnly());
  RenderSettings settings;
  settings.samplesPerPixel = spp;
  settings.threads = threads;
  settings.bounces = bounces;
  settings.seed = seed;
  return atDisplayResolution(d, render(scene, accelerator, camera, settings));
}

namespace {

// flickerBetween on images already sRGB-encoded (srgbEncoded), rows summed in order.
double flickerBetweenEncoded(const Image& simulatedBefore, const Image& idealBefore,
                             const Image& simulated, const Image& ideal) {
  const int width = simulated.width();
  const double sum = parallelSum(simulated.height(), 0, 8, [&](int64_t y) {
    double row = 0;
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double now = double(simulated.at(x, int(y))[c]) - double(ideal.at(x, int(y))[c]);
        const double before =
            double(simulatedBefore.at(x, int(y))[c]) - double(idealBefore.at(x, int(y))[c]);
        row += (now - before) * (now - before);
      }
    return row;
  });
  const size_t n = simulated.pixels().size();
  return n == 0 ? 0.0 : std::sqrt(sum / double(3 * n));
}

}  // namespace

double flickerBetween(const Image& simulatedBefore, const Image& idealBefore,
                      const Image& simulated, const Image& ideal) {
  // (S_i - S_{i-1}) - (R_i - R_{i-1}) = (S_i - R_i) - (S_{i-1} - R_{i-1}), in sRGB values.
  return flickerBetweenEncoded(srgbEncoded(simulatedBefore), srgbEncoded(idealBefore),
                               srgbEncoded(simulated), srgbEncoded(ideal));
}

QualitySummary summarise(const std::vector<EyeQuality>& eyes) {
  QualitySummary s;
  s.worstPsnr = std::numeric_limits<double>::infinity();
  int flickers = 0;
  for (const EyeQuality& q : eyes) {
    ++s.eyes;
    s.meanPsnr += q.psnr;
    s.meanSsim += q.ssim;
    s.meanLuminance += q.meanLuminance;
    if (q.psnr < s.worstPsnr) s.worstPsnr = q.psnr, s.worstEye = q.eye.position;
    if (!std::isnan(q.flicker)) s.meanFlicker += q.flicker, ++flickers;
  }
  if (s.eyes > 0) s.meanPsnr /= s.eyes, s.meanSsim /= s.eyes, s.meanLuminance /= s.eyes;
  s.meanFlicker =
      flickers > 0 ? s.meanFlicker / flickers : std::numeric_limits<double>::quiet_NaN();
  return s;
}

namespace {

// Splits the per-eye scores into the dense summary, the design eyes' and one per distance.
void summariseAll(ViewerQuality& result) {
  std::vector<EyeQuality> dense, design;
  for (const EyeQuality& q : result.eyes) (q.eye.designEye ? design : dense).push_back(q);
  result.all = summarise(dense);
  result.designOnly = summarise(design);
  for (const EyeQuality& q : dense) {
    auto it = std::find_if(result.byDistance.begin(), result.byDistance.end(),
                           [&](const auto& entry) { return entry.first == q.eye.distance; });
    if (it == result.byDistance.end()) result.byDistance.push_back({q.eye.distance, {}});
  }
  for (auto& [distance, summary] : result.byDistance) {
    std::vector<EyeQuality> row;
    for (const EyeQuality& q : dense)
      if (q.eye.distance == distance) row.push_back(q);
    summary = summarise(row);
  }
}

}  // namespace

std::vector<ViewerQuality> measureViewerQuality(
    const Scene& scene, const Accelerator& accelerator, const DisplayModel& display,
    const std::vector<const SimulatedDisplay*>& simulators, const std::vector<DenseEye>& eyes,
    const ViewerQualityOptions& options, const std::function<void(int, int)>& progress) {
  std::vector<ViewerQuality> results(simulators.size());
  if (simulators.empty() || eyes.empty()) return results;
  // Every eye's pictures have the first one's size.
  Image firstSeen = simulators.front()->seen(eyes.front().position);
  const int width = firstSeen.width(), height = firstSeen.height();
  // Eye i's ideal view and its sRGB encoding (for its PSNR and the next eye's flicker).
  const auto renderIdeal = [&](size_t i, Image& ideal, Image& encoded) {
    ideal = idealView(scene, accelerator, display, *simulators.front(), eyes[i].position, width,
                      height, options.referenceSamplesPerPixel, options.threads, options.bounces);
    encoded = srgbEncoded(ideal);
  };
  Image ideal, idealEncoded;
  renderIdeal(0, ideal, idealEncoded);
  std::vector<Image> previousSimulated(simulators.size());
  Image previousIdeal;
  for (size_t i = 0; i < eyes.size(); ++i) {
    const DenseEye& eye = eyes[i];
    // A row is one distance, left to right: the eyes a moving viewer passes in turn.
    const bool sameRow =
        i > 0 && eyes[i - 1].distance == eye.distance && !eye.designEye && !eyes[i - 1].designEye;
    const auto compareEye = [&] {
      for (size_t s = 0; s < simulators.size(); ++s) {
        const Image simulated =
            i == 0 && s == 0 ? std::move(firstSeen) : simulators[s]->seen(eye.position);
        // Encoded, PSNR's and flicker's squares and the luminance in one pass over the rows.
        EncodedComparison compared =
            compareEncoded(simulated, idealEncoded, sameRow ? &previousSimulated[s] : nullptr,
                           sameRow ? &previousIdeal : nullptr);
        const double pixels = double(simulated.pixels().size());
        const double meanSquares = compared.squaredError / (3.0 * pixels);
        EyeQuality q{eye,
                     meanSquares > 0 ? 10.0 * std::log10(1.0 / meanSquares)
                                     : std::numeric_limits<double>::infinity(),
                     ssim(simulated, ideal),
                     sameRow ? std::sqrt(compared.flickerSquares / (3.0 * pixels))
                             : std::numeric_limits<double>::quiet_NaN(),
                     compared.luminance / pixels};
        results[s].eyes.push_back(q);
        previousSimulated[s] = std::move(compared.encoded);
      }
    };
    // The next eye's ideal view is rendered while this eye's pictures are compared, so that
    // either keeps the cores busy through the other's serial parts (set-up, sums, the rows a
    // band leaves idle). Each is computed as alone: the figures do not change.
    Image nextIdeal, nextEncoded;
    if (i + 1 < eyes.size())
      parallelInvoke(options.threads, compareEye,
                     [&] { renderIdeal(i + 1, nextIdeal, nextEncoded); });
    else
      compareEye();
    previousIdeal = std::move(idealEncoded);
    ideal = std::move(nextIdeal);
    idealEncoded = std::move(nextEncoded);
    if (progress) progress(int(i + 1), int(eyes.size()));
  }
  for (ViewerQuality& result : results) summariseAll(result);
  return results;
}

ViewerQuality measureViewerQuality(const Scene& scene, const Accelerator& accelerator,
                                   const DisplayModel& display, const SimulatedDisplay& simulator,
                                   const std::vector<DenseEye>& eyes,
                                   const ViewerQualityOptions& options,
                                   const std::function<void(int, int)>& progress) {
  return measureViewerQuality(scene, accelerator, display, {&simulator}, eyes, options, progress)
      .front();
}

}  // namespace parallax
