#include "parallax/layers/training.h"

#include <chrono>
#include <stdexcept>

#include "parallax/camera/display_camera.h"
#include "parallax/core/parallel.h"
#include "parallax/core/random.h"
#include "parallax/quality/viewer_quality.h"
#include "parallax/render/render.h"
#include "parallax/sim/simulator.h"

namespace parallax {

namespace {

// Training eyes times the front layer's pixels: the pixels of all training views.
double trainingEyeCount(const DisplayDesign& design, const TrainingOptions& options) {
  return double(pixelViewCount(design)) * options.eyesPerView * double(options.distances.size());
}

const Panel& frontPanel(const DisplayDesign& design) {
  return design.spec.order == LayerOrder::BarrierBack ? design.spec.imagePanel
                                                      : design.spec.maskPanel;
}

double trainingPixels(const DisplayDesign& design, const TrainingOptions& options) {
  const Panel& front = frontPanel(design);
  return trainingEyeCount(design, options) * double(front.width) * double(front.height);
}

// The eyes' operators with a pupil: each of its sights holds its pieces across a row (about two
// a column with their weights, runs' weights and starts: under 100 bytes a column) and down a
// column (under 64 bytes a row, its rear rows' sources included; seen_layers.h).
double pupilSightBytes(const DisplayDesign& design, const TrainingOptions& options) {
  if (!(options.pupilDiameterMm > 0)) return 0.0;
  const Panel& front = frontPanel(design);
  return trainingEyeCount(design, options) * double(options.pupilSamples) *
         (100.0 * front.width + 64.0 * front.height);
}

}  // namespace

uint64_t trainingEyeSeed(uint64_t renderSeed, size_t eye) {
  // Draw eye + 1 of SplitMix64's sequence from the render's seed (core/random.h).
  return mix64(renderSeed + 0x9e3779b97f4a7c15ull * (uint64_t(eye) + 1));
}

double seenMaskBytes(const DisplayDesign& design, const TrainingOptions& options) {
  return trainingPixels(design, options) * sizeof(float);
}

double trainingBytes(const DisplayDesign& design, const TrainingOptions& options) {
  // Targets are kept in 16 bits per channel (TrainingView::encodeTarget).
  return trainingPixels(design, options) * 3.0 * sizeof(uint16_t);
}

namespace {

// Whether the targets' rows can be made a band at a time (IdealViewBands): the image in front,
// whose row j every eye's view row j depends on, and a box along rows (a pinhole mask's box
// spans rows).
SeenOptics seenOptics(const TrainingOptions& options) {
  return {.colourFilters = options.colourFilters,
          .rearStripeCells = options.rearStripeCells,
          .pupilDiameterMm = options.pupilDiameterMm,
          .pupilSamples = options.pupilSamples};
}

bool targetRowsByBands(const DisplayDesign& design) {
  return design.spec.order == LayerOrder::BarrierBack &&
         design.spec.mask.kind != MaskKind::Pinholes;
}

}  // namespace

bool solvesByBands(const DisplayDesign& design, const TrainingOptions& options,
                   LayerMethod method) {
  return method == LayerMethod::OptimizedImage && options.srgbWeights && targetRowsByBands(design);
}

double trainingHeldBytes(const DisplayDesign& design, const TrainingOptions& options,
                         LayerMethod method) {
  // The seen masks: a float a pixel for a grey mask; through colour filters three, kept for a
  // band of rows only (image_layer_solver.cpp, ImageLayerPasses).
  const bool bands = solvesByBands(design, options, method);
  double seenMasks = 0;
  if (method == LayerMethod::OptimizedImage)
    seenMasks = !options.colourFilters ? seenMaskBytes(design, options)
                : bands                ? 3.0 * seenMaskBytes(design, options)
                                       : 0.0;
  const double whole = trainingBytes(design, options) + seenMasks;
  const double sights = pupilSightBytes(design, options);
  if (!bands) return whole + sights;
  const Panel& front = design.spec.imagePanel;
  // A band's share, and per worker an eye's band rendered and boxed in floats.
  const double band = std::min(1.0, double(kTargetBandRows) / double(front.height));
  return whole * band + sights +
         imageBytes(front.width, std::min(front.height, kTargetBandRows), kFloatRgbPixelBytes,
                    2.0 * workerCount(options.threads));
}

std::vector<TrainingView> trainingEyes(const DisplayDesign& design,
                                       const TrainingOptions& options) {
  std::vector<TrainingView> views;
  for (const DenseEye& eye : denseEyes(design, options.eyesPerView, options.distances))
    views.push_back({SeenLayers(design, eye.position, seenOptics(options)), Image(),
                     options.srgbWeights ? float(options.targetScale) : 0.0f});
  return views;
}

struct IdealViewBands::Impl {
  const DisplayDesign& design;
  TrainingOptions options;
  std::unique_ptr<DisplayModel> display;
  std::vector<std::unique_ptr<WindowCamera>> cameras;
  std::vector<std::unique_ptr<TileRenderer>> renderers;
  int width = 0, height = 0;
  double seconds = 0;
  // Eye `eye`'s target on rows firstRow .. firstRow + rows - 1: its ideal view on the tiles of
  // those rows, through the display's box along rows, times the target scale.
  Image band(size_t eye, int firstRow, int rows) const;
};

IdealViewBands::IdealViewBands(const Scene& scene, const Accelerator& accelerator,
                               const DisplayDesign& design, const TrainingOptions& options)
    : impl_(std::make_unique<Impl>(Impl{design, options, makeBarrierDisplay(design), {}, {}})) {
  Impl& i = *impl_;
  const Panel& front = design.spec.imagePanel;
  i.width = front.width, i.height = front.height;
  // As idealView renders them (quality/viewer_quality.cpp).
  RenderSettings settings;
  settings.samplesPerPixel = options.referenceSamplesPerPixel;
  settings.bounces = options.bounces;
  size_t index = 0;
  for (const DenseEye& eye : denseEyes(design, options.eyesPerView, options.distances)) {
    settings.seed = trainingEyeSeed(options.seed, index++);
    i.cameras.push_back(std::make_unique<WindowCamera>(eye.position, *i.display, scene.display,
                                                       i.width, i.height,
                                                       i.display->horizontalParallaxOnly()));
    i.renderers.push_back(
        std::make_unique<TileRenderer>(scene, accelerator, *i.cameras.back(), settings));
  }
}

IdealViewBands::~IdealViewBands() = default;

double IdealViewBands::seconds() const {
  return impl_->seconds;
}

Image IdealViewBands::Impl::band(size_t eye, int firstRow, int rows) const {
  const TileRenderer& renderer = *renderers[eye];
  Image band(width, rows);
  RenderStats stats;
  for (int tile = 0; tile < renderer.tileCount(); ++tile) {
    const int band0 = renderer.tileBand(tile) * TileGrid::kRows;
    if (band0 >= firstRow && band0 < firstRow + rows)
      renderer.renderTile(tile, band, firstRow, stats);
  }
  Image target = atDisplayResolution(design, band);
  for (Vec3f& p : target.pixels()) p = p * float(options.targetScale);
  return target;
}

void IdealViewBands::operator()(int firstRow, int rows, std::vector<TrainingView>& views) const {
  Impl& i = *impl_;
  const auto start = std::chrono::steady_clock::now();
  if (views.size() != i.renderers.size() || firstRow % TileGrid::kRows != 0 || rows < 1 ||
      firstRow + rows > i.height)
    throw std::invalid_argument("IdealViewBands: not the training eyes' rows");
  parallelFor(int64_t(views.size()), i.options.threads, 1, [&](int64_t begin, int64_t end) {
    for (int64_t e = begin; e != end; ++e) {
      TrainingView& v = views[size_t(e)];
      v.target = i.band(size_t(e), firstRow, rows);
      v.encodeTarget(1);
      v.firstTargetRow = firstRow;
    }
  });
  i.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void IdealViewBands::wholeBoxedTargets(std::vector<TrainingView>& views,
                                       const std::function<void(int, int)>& progress) const {
  Impl& i = *impl_;
  const auto start = std::chrono::steady_clock::now();
  if (views.size() != i.renderers.size())
    throw std::invalid_argument("IdealViewBands: not the training eyes");
  for (TrainingView& v : views) v.startBoxedTarget();
  const int bands = (i.height + kTargetBandRows - 1) / kTargetBandRows;
  for (int b = 0; b < bands; ++b) {
    const int firstRow = b * kTargetBandRows, rows = std::min(kTargetBandRows, i.height - firstRow);
    parallelFor(int64_t(views.size()), i.options.threads, 1, [&](int64_t begin, int64_t end) {
      for (int64_t e = begin; e != end; ++e) {
        Image target = i.band(size_t(e), firstRow, rows);
        views[size_t(e)].encodeBoxedRows(target.pixels().data(), firstRow, rows);
      }
    });
    if (progress) progress(b + 1, bands);
  }
  i.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<TrainingView> trainingViews(const Scene& scene, const Accelerator& accelerator,
                                        const DisplayDesign& design, const TrainingOptions& options,
                                        const std::function<void(int, int)>& progress) {
  // Boxed targets (nmf, the image in front) are encoded row by row: rendered a band of rows at a
  // time, every eye in parallel, with no whole float view made.
  if (options.boxedTargets && targetRowsByBands(design)) {
    std::vector<TrainingView> views = trainingEyes(design, options);
    IdealViewBands(scene, accelerator, design, options).wholeBoxedTargets(views, progress);
    return views;
  }
  const std::vector<DenseEye> eyes = denseEyes(design, options.eyesPerView, options.distances);
  std::vector<TrainingView> views;
  views.reserve(eyes.size());
  for (size_t i = 0; i < eyes.size(); ++i) {
    SeenLayers seen(design, eyes[i].position, seenOptics(options));
    Image target = idealView(scene, accelerator, design, eyes[i].position, seen.width(),
                             seen.height(), options.referenceSamplesPerPixel, options.threads,
                             options.bounces, trainingEyeSeed(options.seed, i));
    for (Vec3f& p : target.pixels()) p = p * float(options.targetScale);
    views.push_back({std::move(seen), std::move(target),
                     options.srgbWeights ? float(options.targetScale) : 0.0f});
    // Targets kept in 16 bits: half the bytes (and, for the sRGB errors, one encoding less per
    // pass).
    if (options.boxedTargets)
      views.back().encodeBoxedTarget(options.threads);
    else
      views.back().encodeTarget(options.threads);
    if (progress) progress(int(i) + 1, int(eyes.size()));
  }
  return views;
}

double meanTransmittance(const Image& layer) {
  double sum = 0;
  for (const Vec3f& p : layer.pixels()) sum += (double(p.x) + p.y + p.z) / 3.0;
  return layer.empty() ? 0.0 : sum / double(layer.pixels().size());
}

}  // namespace parallax
