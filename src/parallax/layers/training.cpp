#include "parallax/layers/training.h"

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
  // Targets are kept in 16 bits per channel (TrainingView::encodeTarget).
  return trainingPixels(design, options) * 3.0 * sizeof(uint16_t);
}

std::vector<TrainingView> trainingViews(const Scene& scene, const Accelerator& accelerator,
                                        const DisplayDesign& design, const TrainingOptions& options,
                                        const std::function<void(int, int)>& progress) {
  const std::vector<DenseEye> eyes = denseEyes(design, options.eyesPerView, options.distances);
  std::vector<TrainingView> views;
  views.reserve(eyes.size());
  for (size_t i = 0; i < eyes.size(); ++i) {
    SeenLayers seen(design, eyes[i].position);
    Image target =
        idealView(scene, accelerator, design, eyes[i].position, seen.width(), seen.height(),
                  options.referenceSamplesPerPixel, options.threads, options.bounces);
    for (Vec3f& p : target.pixels()) p = p * float(options.targetScale);
    views.push_back({std::move(seen), std::move(target),
                     options.srgbWeights ? float(options.targetScale) : 0.0f});
    // Targets kept in 16 bits: half the bytes (and, for the sRGB errors, one encoding less per
    // pass).
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
