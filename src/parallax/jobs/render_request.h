// The render request (docs/architecture.md, "Requests"): what `parallax render` and Python's
// render functions spell, checked before any work; the runner is render_job.h, its parts
// render_parts.h.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "parallax/image/image.h"
#include "parallax/jobs/display_request.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/scene_request.h"
#include "parallax/jobs/sequence.h"
#include "parallax/layers/layer_method.h"
#include "parallax/layers/layer_problem.h"

namespace parallax::jobs {

// The solvers' iterations when none are asked (docs/content-adaptive.md): in 7, optimized-image's
// steps on the plane of the gradient and the previous step, and nmf's over-relaxed
// multiplicative updates (rank 1 and 3), reach a lower objective than their plain forms (steepest
// descent, plain updates) reached in 10, the default before them.
inline constexpr int kDefaultLayerIterations = 7;

// layers, rank, iterations, brightness, train_eyes, train_distances, train_spp, layer_error,
// diffuser, color_filters, pupil, pupil_samples: content-adaptive
// layers (docs/content-adaptive.md) instead of the slits' own.
struct LayersRequest {
  std::string method = "slits";   // slits, optimized-image or nmf
  int rank = 1;                   // nmf's time-multiplexed frame pairs
  std::optional<int> iterations;  // 1 to 1000; none: kDefaultLayerIterations
  double brightness = 0;          // times the slits' brightness; 0: the method's default
  int trainEyes = 2;              // training eyes per view at each of trainDistances
  // The training eyes' distances in units of D (parseDistances); the dense measure's own
  // eyes sit at 0.8, 1 and 1.25 D between them (docs/content-adaptive.md, "Training eyes").
  std::string trainDistances = "0.8,1,1.25";
  // Samples per pixel of the training eyes' ideal views (1 to 64; none: kDefaultTrainingSpp;
  // TrainingOptions).
  std::optional<int> trainSpp;
  std::string error;  // srgb or linear; "": the method's default
  // The panel's diffuser foil (Gaussian sigma, mm) the layers are solved for; none: the display
  // file's diffuser_sigma_mm.
  std::optional<double> diffuser;
  // Solve through the panels' colour filters (simulate --color-filters: a panel with an RGB or
  // BGR order passes one channel a stripe), so that the layers undo the colour fringes they make.
  bool colorFilters = false;
  // Solve for eyes with a pupil of this diameter (mm; 0: pinhole eyes), each eye's view the
  // average over pupilSamples points of it (simulate --pupil, --pupil-samples).
  double pupil = 0.0;
  int pupilSamples = 16;
  // The method named (after check(): one of the three).
  LayerMethod methodKind() const;
  bool solved() const { return methodKind() != LayerMethod::Slits; }
  // The error measure the image layer is fitted in: srgb for optimized-image, linear for nmf.
  std::string errorMeasure() const;
  // Throws RequestError naming the field of a bad value.
  void check() const;
};

// quilt (its layout) and size (one view's): the views of a quilt instead of the layers.
struct QuiltRequest {
  bool wanted = false;
  int columns = 0, rows = 0;  // 0: the display's own (a device's quilt, a barrier's row of views)
  int width = 0, height = 0;  // one view; 0: the device quilt's tile, or the panel's resolution
};

struct RenderRequest {
  SceneRequest scene;
  // "" the built-in barrier, a display file, a calibration, lkg:NAME; subpixels (one ray per R,
  // G, B subpixel of a barrier), distance (a lenticular panel's design viewer) and the lens
  // reading to render for, as simulate reads them (docs/lenticular.md, "The optics").
  DisplayRequest display;
  SamplingRequest sampling;
  FilterRequest filter;
  FramingRequest framing;
  bool directMapping = false;  // direct_mapping: N ordinary views, interleaved (Fig. 2)
  bool linear = false;         // also image.pfm (a quilt: its .pfm)
  QuiltRequest quilt;
  LayersRequest layers;
  SequenceRequest sequence;  // frames, chunk, turntable, duration, fps, video
  std::string output = "out";
};

// One picture set in memory (Python): the image layer (a lenticular panel's picture) and mask
// of each frame (one, or nmf's rank), or the quilt; and render.json's record.
struct RenderResult {
  std::vector<LayerFrame> frames;  // mask empty for a display without one
  Image quilt;                     // linear; with quilt.wanted
  std::string record;
};

}  // namespace parallax::jobs
