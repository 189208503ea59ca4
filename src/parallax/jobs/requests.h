// The typed requests every runner shares (docs/architecture.md, "Requests"): how to sample,
// how a display pixel's rays spread and how the content is framed; which scene is
// scene_request.h's, which display display_request.h's. Plain values that a front end fills from
// its own spelling (the CLI's --spp, Python's spp=); each check throws RequestError naming the
// field as the request spells it ("spp", "depth_budget").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "parallax/camera/framing.h"
#include "parallax/display/view_filter.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/reporter.h"
#include "parallax/render/render_settings.h"
#include "parallax/scene/scene.h"

namespace parallax::jobs {

// "parallax 0.1.0 (Embree 4.3.3, assimp 5.4.3)": this build's version and the libraries it
// runs on.
std::string versionText();

// The text as a whole number, or false: decimal digits with an optional leading minus, no
// spaces, within int64_t.
bool parseInteger(const std::string& text, int64_t& value);
// The text as a finite real number filling all of it, or false.
bool parseNumber(const std::string& text, double& value);
// "WxH" -> (W, H) with both positive; throws InputError naming the option. Memory (and the
// pixel count) are checked separately, with the estimate.
void parseSize(const std::string& option, const std::string& text, int& width, int& height);

// Refuses a worker-thread count below 0 (0: all cores) or above this machine's hardware
// threads, as the command line's validator does (Python's threads= reaches only this).
void checkThreads(int threads);

// "0.8,1,1.25": eye distances in units of the design distance D, each 0.1 to 10 (the dense
// measure's --distances, the training eyes' --train-distances); RequestError naming `field`.
std::vector<double> parseDistances(const std::string& text, const std::string& field);

// spp, threads, seed, jitter, adaptive, adaptive_threshold, bounces.
struct SamplingRequest {
  int spp = 16;
  int threads = 0;
  uint64_t seed = 0;
  std::string jitter = "auto";
  bool adaptive = false;
  int bounces = 0;  // diffuse path-tracing bounces (RenderSettings::bounces)
  double adaptiveThreshold = RenderSettings{}.adaptiveThreshold * 255.0;  // in 8-bit steps
  // The render settings; throws RequestError naming spp (below 1), threads, jitter (not auto,
  // pixel or packet), adaptive_threshold (outside 0 to 255) or bounces.
  RenderSettings settings() const;
  // Refuses spp when width x height x spp x `passes` samples exceed the time limit.
  void checkWork(double width, double height, double passes = 1.0) const;
};

// filter, filter_width: how a display pixel's rays spread in angle (display/view_filter.h).
struct FilterRequest {
  std::string kind = viewFilterName(ViewFilter{}.kind);
  double widthViews = ViewFilter{}.widthViews;
  // Throws RequestError naming filter (an unknown kind) or filter_width (outside [0.05, 20]).
  ViewFilter filter() const;
};

// fit, focus, depth_budget: how the content is framed for the display (camera/framing.h).
// Empty: the scene's own choice.
struct FramingRequest {
  std::string fit, focus, depthBudget;
  bool given() const { return !fit.empty() || !focus.empty() || !depthBudget.empty(); }
  // Sets them on the scene's placement; throws RequestError naming the field.
  void apply(DisplayPlacement& placement) const {
    applyFramingOptions(placement, fit, focus, depthBudget);
  }
  // Refuses bad values before anything is loaded.
  void check() const;
};

// The framing's figures (camera/framing.h) under `at` ("/framing"): fit, focus, gaps, depth
// of field and budget, and the content's near and far as given and as shown.
void setFramingFigures(JsonWriter& json, const std::string& at, const Framing& framing);
// The framing in render.json, under "/framing": what was asked (fit, focus, depth_budget:
// simulate --reference frames the scene again from these) and what followed.
void recordFraming(JsonWriter& record, const Framing& framing);

}  // namespace parallax::jobs
