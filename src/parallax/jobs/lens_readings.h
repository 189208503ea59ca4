// A lens sheet's optics as the simulator reads them (docs/lenticular.md, "The optics"): the
// reading a request asks for, the readings --all-readings scores under, and the line that says
// which one is used. The lenticular panel's own, asked of any display: a display without lenses
// has no readings.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "parallax/display/display_model.h"
#include "parallax/jobs/display_request.h"
#include "parallax/sim/simulator.h"

namespace parallax::jobs {

// The lens reading (unset: the display's own optics) for `display`; refused (RequestError
// naming lens_spot or bundles) for a display without lenses.
std::optional<LensOptics> lensReading(const DisplayModel& display, const LensReadingRequest& lens);

// The readings --all-readings scores under: an ideal lens and a pixel-wide spot (0 and 3
// subpixels), each with parallel and with converging bundles, then the design's own; with a
// label each ("spot 0, parallel"); none for a display without lenses.
std::vector<std::pair<std::string, LensOptics>> lensReadings(const DisplayModel& display);

// The reading a lenticular simulator uses, in words ("seen through lenses with a 1-subpixel
// focal spot, bundles converging at 1374 mm"); "" for other kinds.
std::string lensReadingLine(const DisplayModel& display, const SimulationOptions& options);

}  // namespace parallax::jobs
