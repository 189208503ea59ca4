// Content-adaptive layers from the slit layers (docs/content-adaptive.md): the training views at
// eyes across the view zone, then the optimised image layer or the weighted NMF of both layers.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "parallax/core/memory.h"
#include "parallax/jobs/render_parts.h"
#include "parallax/layers/image_layer_solver.h"
#include "parallax/layers/layer_factorization.h"
#include "parallax/layers/layer_method.h"
#include "parallax/layers/training.h"

namespace parallax::jobs {

namespace {

// nmf aims 5 % above max(2, rank) times the slits' brightness: a least-squares fit comes out a
// little darker than its target (measured: 1.97x for a target of 2 on the built-in scene).
double defaultBrightness(LayerMethod method, int rank) {
  return method == LayerMethod::Nmf ? 1.05 * std::max(2.0, double(rank)) : 1.0;
}

// nmf's start: T copies of the slit image; masks of T slit phases a period / T apart, their
// closed pixels at 0.2 so that the updates can open them (a zero stays zero under them).
std::vector<LayerFrame> nmfStart(const LayerFrame& slits, double periodPx, int rank) {
  std::vector<LayerFrame> frames;
  for (int t = 0; t < rank; ++t) {
    Image mask = slits.mask;
    const int shift = int(std::lround(periodPx * t / rank));
    for (int y = 0; y < mask.height(); ++y)
      for (int x = 0; x < mask.width(); ++x) {
        const int from = std::clamp(x - shift, 0, mask.width() - 1);
        const Vec3f v = slits.mask.at(from, y);
        mask.at(x, y) = Vec3f(std::max(v.x, 0.2f), std::max(v.y, 0.2f), std::max(v.z, 0.2f));
      }
    frames.push_back({slits.image, std::move(mask)});
  }
  return frames;
}

}  // namespace

const DisplayDesign& solvedBarrier(const DisplayModel& display) {
  if (const DisplayDesign* barrier = display.barrierDesign()) return *barrier;
  throw std::logic_error("solvedBarrier: layers are solved for a display with a mask layer");
}

double layerSolveBytes(const DisplayDesign& design, const LayersRequest& request,
                       const TrainingOptions& training) {
  const Panel& panel = design.spec.imagePanel;
  return trainingHeldBytes(design, training, request.methodKind()) +
         double(panel.width) * panel.height * sizeof(Vec3f) * (4.0 * request.rank + 6.0);
}

TrainingOptions trainingOptions(const LayersRequest& request, int threads, int bounces,
                                uint64_t seed) {
  TrainingOptions training;
  training.eyesPerView = request.trainEyes;
  training.referenceSamplesPerPixel = request.trainSpp.value_or(kDefaultTrainingSpp);
  training.seed = seed;
  training.distances = parseDistances(request.trainDistances, "train_distances");
  training.srgbWeights = request.errorMeasure() == "srgb";
  training.colourFilters = request.colorFilters;
  training.pupilDiameterMm = request.pupil;
  training.pupilSamples = request.pupilSamples;
  training.threads = threads;
  training.bounces = bounces;
  return training;
}

std::vector<LayerFrame> solveLayers(const LayersRequest& o, const Scene& scene,
                                    const Accelerator& accelerator, const DisplayDesign& design,
                                    TrainingOptions training, const LayerFrame& slits,
                                    JsonWriter& out, Reporter& reporter,
                                    LayerSolveFigures* figures) {
  const auto start = std::chrono::steady_clock::now();
  // The per-eye pictures and the solver's per-iteration images come and go at two or three
  // sizes: their blocks are taken again rather than handed back to the kernel.
  const KeepFreedBlocks keepFreedBlocks;
  const double slitMean = meanTransmittance(slits.mask);
  const double gain = o.brightness > 0 ? o.brightness : defaultBrightness(o.methodKind(), o.rank);
  training.targetScale = slitMean * gain;
  const int iterations = o.iterations.value_or(kDefaultLayerIterations);
  // A diffuser foil blurs the rear layer (sim/diffuser.h); its pixels are the rear panel's.
  const Panel& rear =
      design.spec.order == LayerOrder::BarrierBack ? design.spec.maskPanel : design.spec.imagePanel;
  // Through the colour filters it blurs the light the rear stripes pass (RearDiffuser::stripes).
  const RearDiffuser diffuser{o.diffuser.value_or(design.spec.diffuserSigmaMm), rear.pitchMm,
                              o.colorFilters ? rear.subpixels : SubpixelOrder::None};
  training.rearStripeCells = diffuser.striped();
  SolveReport report;
  std::vector<LayerFrame> frames;
  std::vector<TrainingView> views;
  double trainSeconds = 0;
  // The solve's progress bar: it lives for the solve only (it goes before the result line).
  std::unique_ptr<Progress> progress;
  const SolveProgress onIteration = [&](int done, int total, double objective) {
    progress->detail(printed("objective %.4g", objective));
    progress->update(done, total);
  };
  if (solvesByBands(design, training, o.methodKind())) {
    // The ideal views a band of rows at a time, each band solved before the next is rendered:
    // one band's targets held instead of every eye's whole view (layers/training.h).
    views = trainingEyes(design, training);
    const IdealViewBands bands(scene, accelerator, design, training);
    progress = reporter.progress("ideal views and layers " + o.method);
    frames.push_back({optimizeImageLayerByBands(views, std::cref(bands), kTargetBandRows,
                                                slits.image, slits.mask, iterations,
                                                training.threads, &report, onIteration, diffuser),
                      slits.mask});
    trainSeconds = bands.seconds();
  } else {
    // nmf with the image in front reads the targets only through B^T (TrainingView::boxedTarget).
    training.boxedTargets =
        o.methodKind() == LayerMethod::Nmf && design.spec.order == LayerOrder::BarrierBack;
    {
      const auto viewsProgress = reporter.progress("ideal views");
      views = trainingViews(scene, accelerator, design, training, viewsProgress->callback());
    }
    trainSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    progress = reporter.progress("layers " + o.method);
    if (o.methodKind() == LayerMethod::OptimizedImage)
      frames.push_back({optimizeImageLayer(views, slits.image, slits.mask, iterations,
                                           training.threads, &report, onIteration, diffuser),
                        slits.mask});
    else
      frames = factorizeLayers(views, nmfStart(slits, design.slitPeriodPx, o.rank), iterations,
                               training.threads, &report, onIteration, diffuser);
  }
  progress.reset();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double seen = 0;
  for (const LayerFrame& f : frames) seen += meanTransmittance(f.image) * meanTransmittance(f.mask);
  out.set("/layers/rank", int(frames.size()));
  out.set("/layers/iterations", report.iterations);
  out.set("/layers/brightness_gain", gain);
  // simulate divides what the eye sees by this (the slit mask's mean transmittance times the
  // gain), so that views compare with the ideal ones at the brightness the layers aimed at.
  out.set("/layers/normalisation", slitMean * gain);
  out.set("/layers/training_eyes", int(views.size()));
  for (size_t i = 0; i < training.distances.size(); ++i)
    out.set("/layers/training_distances/" + std::to_string(i), training.distances[i]);
  out.set("/layers/train_spp", training.referenceSamplesPerPixel);
  out.set("/layers/error", o.errorMeasure());
  out.set("/layers/diffuser_sigma_mm", diffuser.sigmaMm);
  out.set("/layers/color_filters", o.colorFilters);
  out.set("/layers/pupil_mm", o.pupil);
  out.set("/layers/pupil_samples", o.pupil > 0 ? o.pupilSamples : 1);
  out.set("/layers/training_seconds", trainSeconds);
  out.set("/layers/seconds", seconds);
  out.set("/layers/passes", report.passes);
  if (figures)
    *figures = {trainSeconds,      seconds - trainSeconds, trainingBytes(design, training),
                int(views.size()), report.iterations,      report.passes};
  out.set("/layers/objective_first", report.objective.front());
  out.set("/layers/objective_last", report.objective.back());
  out.set("/layers/mean_layer_product", seen / double(frames.size()));
  reporter.result(
      printed("%s: %zu frame(s), %d iterations, objective %.3g -> %.3g (per pixel and channel), "
              "%zu training eyes, %.1f s (ideal views %.1f s)",
              o.method.c_str(), frames.size(), report.iterations, report.objective.front(),
              report.objective.back(), views.size(), seconds, trainSeconds));
  return frames;
}

}  // namespace parallax::jobs
