// The render request's checks (render_request.h).
#include "parallax/jobs/render_request.h"

#include "parallax/core/error.h"

namespace parallax::jobs {

std::string LayersRequest::errorMeasure() const {
  if (!error.empty()) return error;
  return methodKind() == LayerMethod::OptimizedImage ? "srgb" : "linear";
}

LayerMethod LayersRequest::methodKind() const {
  const std::optional<LayerMethod> kind = layerMethodNamed(method);
  if (!kind)
    throw RequestError("layers", "expected slits, optimized-image or nmf, got '" + method + "'");
  return *kind;
}

void LayersRequest::check() const {
  const LayerMethod kind = methodKind();
  if (rank < 1 || rank > 16) throw RequestError("rank", "must be between 1 and 16 frames");
  if (rank > 1 && kind != LayerMethod::Nmf)
    throw RequestError("rank", "time-multiplexed frames need {layers} nmf");
  // A solver's own settings: refused, not ignored, without a solver (and 0 iterations is no
  // default: a solver runs at least once).
  if (iterations && (*iterations < 1 || *iterations > 1000))
    throw RequestError("iterations", "must be between 1 and 1000");
  if (iterations && !solved())
    throw RequestError("iterations",
                       "applies to {layers} optimized-image or nmf (slits solve nothing)");
  if (!(brightness >= 0) || brightness > 100)
    throw RequestError("brightness", "must be between 0 (default) and 100");
  if (brightness > 0 && !solved())
    throw RequestError("brightness",
                       "applies to {layers} optimized-image or nmf (slits have the brightness of "
                       "their duty cycle)");
  if (!error.empty() && error != "linear" && error != "srgb")
    throw RequestError("layer_error", "expected linear or srgb, got '" + error + "'");
  if (!error.empty() && !solved())
    throw RequestError("layer_error", "applies to {layers} optimized-image or nmf");
  if (errorMeasure() == "srgb" && kind != LayerMethod::OptimizedImage)
    throw RequestError("layer_error",
                       "srgb is for {layers} optimized-image (nmf's updates fit in linear light)");
  if (trainEyes < 1 || trainEyes > 16)
    throw RequestError("train_eyes", "must be between 1 and 16 eyes per view");
  if (trainSpp && !solved())
    throw RequestError("train_spp",
                       "applies to {layers} optimized-image or nmf (slits solve nothing)");
  if (trainSpp && (*trainSpp < 1 || *trainSpp > 64))
    throw RequestError("train_spp", "must be a whole number from 1 to 64 samples per pixel");
  if (parseDistances(trainDistances, "train_distances").size() > 8)
    throw RequestError("train_distances", "at most 8 distances, got '" + trainDistances + "'");
  if (diffuser && (!(*diffuser >= 0) || !std::isfinite(*diffuser) || *diffuser > 100))
    throw RequestError("diffuser", "must be a blur of 0 to 100 mm (Gaussian sigma)");
  if (diffuser && *diffuser > 0 && !solved())
    throw RequestError("diffuser",
                       "applies to {layers} optimized-image or nmf (the layers solved for a "
                       "panel with a diffuser foil); slits are the same with or without one");
  if (!(pupil >= 0 && pupil <= 100))
    throw RequestError("pupil", "must be a number from 0 to 100 (mm; 0: a pinhole eye)");
  if (pupil > 0 && !solved())
    throw RequestError("pupil",
                       "applies to {layers} optimized-image or nmf (the layers solved "
                       "for eyes with a pupil); slits are the same for any eye");
  // Each sample is a pinhole eye of the solve's operator: the solve's time grows with them.
  if (pupilSamples < 1 || pupilSamples > 64)
    throw RequestError("pupil_samples", "must be a whole number from 1 to 64");
  if (colorFilters && !solved())
    throw RequestError("color_filters",
                       "applies to {layers} optimized-image or nmf (the layers solved for the "
                       "panels' colour filters); slits are the same with or without them");
}

}  // namespace parallax::jobs
