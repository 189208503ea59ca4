#include "parallax/layers/training.h"

#include "parallax/core/parallel.h"
#include "parallax/quality/viewer_quality.h"

namespace parallax {

namespace {

// Training eyes times the front layer's pixels: the pixels of all training views.
double trainingPixels(const DisplayDesign& design, const TrainingOptions& options) {
  const Panel& front =
      design.spec.order == LayerOrder::BarrierBack ? design.spec.imagePanel : design.spec.maskPanel;
  const double eyes =
      double(pixelViewCount(design)) * options.eyesPerView * double(options.distances.size());
  return eyes * double(front.width) * double(front.height);
}

}  // namespace

double seenMaskBytes(const DisplayDesign& design, const TrainingOptions& options) {
  return trainingPixels(design, options) * sizeof(float);
}

double trainingBytes(const DisplayDesign& design, const TrainingOptions& options) {
  // sRGB errors keep their targets encoded in 16 bits per channel (TrainingView::encodeTarget).
  const double perPixel = options.srgbWeights ? 3.0 * sizeof(uint16_t) : double(sizeof(Vec3f));
  return trainingPixels(design, options) * perPixel;
}

std::vector<TrainingView> trainingViews(const Scene& scene, const Accelerator& accelerator,
                                        const DisplayDesign& design, const TrainingOptions& options,
                                        const std::function<void(int, int)>& progress) {
  const std::vector<DenseEye> eyes = denseEyes(design, options.eyesPerView, options.distances);
  std::vector<TrainingView> views;
  views.reserve(eyes.size());
  if (eyes.empty()) return views;
  const auto render = [&](size_t i) {
    const Panel& front = design.spec.order == LayerOrder::BarrierBack ? design.spec.imagePanel
                                                                      : design.spec.maskPanel;
    return idealView(scene, accelerator, design, eyes[i].position, front.width, front.height,
                     options.referenceSamplesPerPixel, options.threads, options.bounces);
  };
  Image target = render(0);
  for (size_t i = 0; i < eyes.size(); ++i) {
    const auto keep = [&] {
      SeenLayers seen(design, eyes[i].position);
      for (Vec3f& p : target.pixels()) p = p * float(options.targetScale);
      views.push_back({std::move(seen), std::move(target),
                       options.srgbWeights ? float(options.targetScale) : 0.0f});
      // The sRGB errors read the target encoded: half the bytes, one encoding less per pass.
      if (options.srgbWeights) views.back().encodeTarget(options.threads);
    };
    // The next eye's ideal view is rendered while this one is kept, so that either keeps the
    // cores busy through the other's serial parts; each is computed as alone.
    Image next;
    if (i + 1 < eyes.size())
      parallelInvoke(options.threads, keep, [&] { next = render(i + 1); });
    else
      keep();
    target = std::move(next);
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
