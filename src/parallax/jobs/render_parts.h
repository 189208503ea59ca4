// The render runner's parts (jobs/render_job.h), internal to jobs: the checked plan, and one
// frame's pictures (layers or a quilt) rendered, solved and recorded.
#pragma once

#include <string>

#include "parallax/accel/accelerator.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/render_request.h"
#include "parallax/layers/training.h"
#include "parallax/render/quilt.h"

namespace parallax::jobs {

// A render request checked against its display, before the scene is loaded.
struct RenderPlan {
  RenderSettings settings;  // one sample per pixel when every sample is the same ray
  ViewFilter filter;
  // The display, designed once; the render frames the scene for it (frameDisplay), which takes
  // it from the plan.
  BuiltDisplay display;
  QuiltLayout layout;  // a quilt's: resolved (auto: the display's own), with the display's aspect
  int tileWidth = 0, tileHeight = 0;
  TrainingOptions training;  // content-adaptive layers' training eyes
  // The files one picture set writes (OutputSet::check, before the scene is loaded).
  std::vector<std::string> outputNames;
  int pictureWidth = 0, pictureHeight = 0;  // a sequence's video frame: the image layer or quilt
};

// Where one frame's pictures go: the request, its plan and display, the sequence (if any) and
// the folder.
struct FrameTarget {
  const RenderRequest* request;
  const RenderPlan* plan;
  const BuiltDisplay* display;
  const SequencePlan* sequence;  // null: one picture set
  int frame;
  std::string output;
  const MadeFrom* madeFrom = nullptr;  // a sequence's frames: what they are made from
};

// The quilt's layout and tile size for `display`, refusing what does not fit (memory, pixels,
// time) and noting tiles whose aspect is not the window's.
void planQuilt(const RenderRequest& request, const DisplayModel& display, RenderPlan& plan,
               Reporter& reporter);

// Refuses (naming `subject`, the display) layers that would not fit in memory, and samples that
// would take too long: the film (and with direct mapping one view per interleaved view), the
// pictures and their 8-bit copies.
void checkPictureWork(const DisplayModel& display, bool directMapping,
                      const RenderSettings& settings, const std::string& subject);

// The whole render's estimate (docs/inputs.md, "Memory"), once the scene is loaded and before
// the BVH is built: what the process holds, Embree's BVH and one frame's pictures at their peak.
// Refuses over the memory limit naming `subject`; under --estimate it stops here. `inMemory`: the
// pictures are handed to the caller, who copies them (Python's arrays), instead of PNG files.
void checkRenderMemory(const RenderRequest& request, const RenderPlan& plan,
                       const DisplayModel& display, const Scene& scene, const std::string& subject,
                       bool inMemory);

// The accelerator for the camera rays the request traces (their count picks its build).
AcceleratorOptions cameraRayAccelerator(const RenderRequest& request, const RenderPlan& plan,
                                        const DisplayModel& display);

// One frame of `scene` rendered and written to target.output (under mpirun: split over the
// ranks, written by rank 0).
void renderFrameToFiles(const FrameTarget& target, const Scene& scene,
                        const Accelerator& accelerator, Reporter& reporter);

// The same frame kept in memory.
RenderResult renderFrameInMemory(const FrameTarget& target, const Scene& scene,
                                 const Accelerator& accelerator, Reporter& reporter);

// What a layer solve took, for `bench --layers`.
struct LayerSolveFigures {
  double trainingSeconds = 0, solveSeconds = 0;  // the ideal views; the solver after them
  double targetBytes = 0;                        // the training targets, as the solver reads them
  int eyes = 0, iterations = 0, passes = 0;      // passes: SolveReport::passes
};

// The training eyes a layers request asks for (train_eyes, train_distances, the error measure),
// rendered on `threads` workers with `bounces` (render's and bench's).
TrainingOptions trainingOptions(const LayersRequest& request, int threads, int bounces = 0,
                                uint64_t seed = 0);

// Layers are solved for a barrier, the one kind with a mask layer (a display without one is
// refused by name before): its design.
const DisplayDesign& solvedBarrier(const DisplayModel& display);
// What a solve holds at its peak: the training targets and, per frame, two layers and their
// gradients.
double layerSolveBytes(const DisplayDesign& design, const LayersRequest& request,
                       const TrainingOptions& training);

// Content-adaptive layers from the slit layers (docs/content-adaptive.md): the training views,
// then the solver; its figures go under /layers of `record` (and into `figures`).
std::vector<LayerFrame> solveLayers(const LayersRequest& request, const Scene& scene,
                                    const Accelerator& accelerator, const DisplayDesign& design,
                                    TrainingOptions training, const LayerFrame& slits,
                                    JsonWriter& record, Reporter& reporter,
                                    LayerSolveFigures* figures = nullptr);

}  // namespace parallax::jobs
