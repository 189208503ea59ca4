// The simulate runner's parts (jobs/simulate_job.h), internal to jobs: the inputs read from a
// render folder, and the dense quality measure.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "parallax/display/display_model.h"
#include "parallax/jobs/reporter.h"
#include "parallax/jobs/simulate_job.h"
#include "parallax/sim/simulator.h"

namespace parallax::jobs {

// The layers of a render folder: its frames when render.json lists them (/frames), else
// image.png and mask.png; and the normalisation optimised layers aimed at.
struct LayerSet {
  std::vector<LayerImages> frames;
  double normalisation = 0;  // render.json's /layers/normalisation (0: the mask's mean)
};
LayerSet loadLayerSet(const std::string& dir, bool hasMask);

// The inputs: a `render` output folder, or its pictures with a display file, of any kind.
struct SimulateInputs {
  std::unique_ptr<DisplayModel> display;
  LayerImages layers;               // the first frame
  std::vector<LayerImages> frames;  // every frame (render --layers nmf --rank T), layers first
  double normalisation = 0;         // render.json's /layers/normalisation (0: the mask's mean)
  std::string scene;                // for reference: the scene the layers were rendered from
};
SimulateInputs loadSimulateInputs(const SimulateRequest& request, Reporter& reporter);

// The scene the layers were rendered from, as they framed it, and the display as the render's
// camera saw it (referenceScene; its display views in.display).
RenderedReference renderedScene(const SimulateInputs& in, const SimulateRequest& request);

// reference without eyes or a sweep: the dense measure (docs/simulator.md), K eyes inside
// every view's window at several distances and the design eyes as their own column; with
// compare, more renders scored side by side.
void runDenseReference(const SimulateRequest& request, const SimulateInputs& in,
                       const SimulationOptions& sim, Reporter& reporter);

}  // namespace parallax::jobs
