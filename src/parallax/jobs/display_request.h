// The display a request names (docs/architecture.md, "Requests"), declared once for every
// command and binding: where its description comes from (a path, or one already loaded), and the
// camera's choices for it (subpixel rays, a lenticular panel's viewer distance, the lens reading
// to render or read the panel under). Choices, not the display's physical description: the
// factory (display_factory.h) makes the model from both.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "parallax/display/display_model.h"
#include "parallax/display/view_filter.h"
#include "parallax/io/display_file.h"
#include "parallax/jobs/reporter.h"

namespace parallax::jobs {

// lens_spot and bundles: a lenticular panel's optics to render for, or to read the panel under
// (docs/lenticular.md, "The optics"); each unset: the display's own.
struct LensReadingRequest {
  std::optional<double> spot;  // lens_spot: the focal spot in subpixels (0: an ideal lens)
  std::string bundles;         // parallel or converging; "": the display's own
  bool given() const { return spot.has_value() || !bundles.empty(); }
};

// The camera's choices for a display: render settings, not part of its physical description.
struct DisplayCameraRequest {
  bool subpixels = false;     // subpixels: one ray per R, G, B subpixel (barriers)
  ViewFilter filter;          // how a film sample's rays spread in angle
  double viewDistanceMm = 0;  // distance: a lenticular panel's design viewer (0: its default)
  LensReadingRequest lens;
};

// display (its path), and the camera's choices that the command has.
struct DisplayRequest {
  // "" the command's default (most: the built-in barrier), a display file of either kind, a
  // calibration (visual.json), or lkg:NAME.
  std::string path;
  // The display already loaded (Python's Display, a calibration in hand); else path's.
  std::optional<DisplayDescription> loaded;
  bool subpixels = false;  // subpixels (render, interlace)
  double distance = 0;     // distance: a lenticular panel's design viewer in mm (0: its default)
  LensReadingRequest lens;
  // Or a display made in code, a kind with no file (a test's third kind, a library user's own
  // panel): its model for the camera's choices. Runners take it through the factory
  // (buildDisplay) as they take a description (describe() gives one of kind Other, read from
  // nowhere); what only a kind with a file has (its file in an output set, a barrier's layers) it
  // goes without.
  std::function<std::unique_ptr<DisplayModel>(const DisplayCameraRequest&)> madeInCode;

  // A request for a description in hand, named by its source unless it is the built-in one.
  static DisplayRequest of(const DisplayDescription& description);

  // The description: loaded, else the file at path (at `whenEmpty` when path is "": "" the
  // built-in barrier), the reader's warnings (defaulted or unknown calibration keys) to
  // `reporter`. Throws InputError naming the file and the key.
  DisplayDescription describe(Reporter& reporter, const std::string& whenEmpty = "") const;
  // The camera's choices, with the view filter a render asks for.
  DisplayCameraRequest camera(const ViewFilter& filter = {}) const;
  // How messages name the display: its path, or `builtIn` when none is given.
  std::string named(const std::string& builtIn = "<built-in display>") const {
    return path.empty() ? builtIn : path;
  }
};

// A display of any kind (io/display_file.h: "" the built-in barrier, a file of either kind, or
// lkg:NAME), the reader's warnings to `reporter`.
DisplayDescription loadDisplay(const std::string& pathOrPreset, Reporter& reporter);

}  // namespace parallax::jobs
