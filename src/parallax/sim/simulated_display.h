// One simulator for every kind of display: what an eye sees, whatever the optics. The two-layer
// barrier is seen through both layers (simulator.h); a lenticular panel through its lenses
// (lenticular_sim.h). Callers (simulate, the dense measure) ask only this.
#pragma once

#include <memory>
#include <vector>

#include "parallax/display/display_model.h"
#include "parallax/image/image.h"
#include "parallax/sim/simulator.h"

namespace parallax {

class SimulatedDisplay {
 public:
  virtual ~SimulatedDisplay() = default;
  // What an eye at eyeMm (display mm, z > 0) sees, in linear light, as the viewer sees it
  // (row 0 at the top, x to the viewer's right).
  virtual Image view(const Vec3d& eyeMm) const = 0;
  // The picture at the display's spatial resolution (a box one aperture period, or one lens,
  // across), as a viewer at the design distance perceives it: both the simulated and the ideal
  // view are brought to it before they are compared.
  virtual Image atDisplayResolution(const Image& image) const = 0;
  // atDisplayResolution(view(eyeMm)), which a kind may make in one pass.
  virtual Image seen(const Vec3d& eyeMm) const { return atDisplayResolution(view(eyeMm)); }
};

// `layers`: the panel's picture (layers.image) and, for kinds with one, the mask layer. Throws
// InputError naming the display's file when a layer's size differs from its panel. `options`
// apply to the two-layer simulator; a lenticular one takes its eye only.
std::unique_ptr<SimulatedDisplay> simulateDisplay(const DisplayModel& display, LayerImages layers,
                                                  const SimulationOptions& options = {});

// Time-multiplexed layers: frame pairs shown in turn faster than the eye follows, seen as the
// average of their views (each through `options`). One frame is simulateDisplay's own.
std::unique_ptr<SimulatedDisplay> simulateDisplay(const DisplayModel& display,
                                                  std::vector<LayerImages> frames,
                                                  const SimulationOptions& options = {});

}  // namespace parallax
