#include "parallax/jobs/requests.h"

#include <charconv>
#include <cmath>
#include <thread>

#include "parallax/accel/accelerator.h"
#include "parallax/core/error.h"
#include "parallax/importer/assimp_importer.h"
#include "parallax/jobs/limits.h"

namespace parallax::jobs {

std::string versionText() {
  const LibraryVersion assimp = assimpVersion();
  return std::string("parallax ") + PARALLAX_VERSION + " (" + embreeLibrary().name() + ", assimp " +
         std::to_string(assimp.major) + "." + std::to_string(assimp.minor) + "." +
         std::to_string(assimp.patch) + ")";
}

namespace {

JitterSharing parseJitter(const std::string& text) {
  if (text == "auto") return JitterSharing::Auto;
  if (text == "pixel") return JitterSharing::Pixel;
  if (text == "packet") return JitterSharing::Packet;
  throw RequestError("jitter", "expected auto, pixel or packet, got '" + text + "'");
}

}  // namespace

bool parseNumber(const std::string& text, double& value) {
  const char* end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && stop == end && std::isfinite(value);
}

std::vector<double> parseDistances(const std::string& text, const std::string& field) {
  std::vector<double> distances;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, end - start);
    char* rest = nullptr;
    const double f = std::strtod(item.c_str(), &rest);
    if (item.empty() || *rest != '\0' || !(f >= 0.1 && f <= 10))
      throw RequestError(field,
                         "expected distances in units of D between 0.1 and 10, separated by "
                         "commas, got '" +
                             text + "'");
    distances.push_back(f);
    start = end + 1;
  }
  return distances;
}

bool parseInteger(const std::string& text, int64_t& value) {
  if (text.empty() || text.size() > 20) return false;
  for (size_t i = 0; i < text.size(); ++i)
    if (!(std::isdigit(static_cast<unsigned char>(text[i])) || (i == 0 && text[i] == '-')))
      return false;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size()) return false;
  value = v;
  return true;
}

void parseSize(const std::string& option, const std::string& text, int& width, int& height) {
  const size_t x = text.find_first_of("xX");
  int64_t w = 0, h = 0;
  if (x == std::string::npos || !parseInteger(text.substr(0, x), w) ||
      !parseInteger(text.substr(x + 1), h) || w <= 0 || h <= 0)
    throw InputError(option, "",
                     "expected WIDTHxHEIGHT (positive whole numbers), got '" + text + "'");
  if (w > INT_MAX || h > INT_MAX)
    throw InputError(option + " " + text, "", "is more pixels across than an int holds");
  width = int(w);
  height = int(h);
}

void checkThreads(int threads) {
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  if (threads < 0 || threads > cores)
    throw RequestError(
        "threads",
        "must be 0 (all cores) to " + std::to_string(cores) + " (this machine's hardware threads)",
        std::to_string(threads));
}

RenderSettings SamplingRequest::settings() const {
  if (spp < 1) throw RequestError("spp", "must be at least 1");
  checkThreads(threads);
  if (!(adaptiveThreshold >= 0 && adaptiveThreshold <= 255))
    throw RequestError("adaptive_threshold", "must be a number from 0 to 255");
  RenderSettings s;
  s.samplesPerPixel = spp;
  s.threads = threads;
  s.seed = seed;
  s.jitter = parseJitter(jitter);
  s.adaptive = adaptive;
  s.adaptiveThreshold = adaptiveThreshold / 255.0;
  if (bounces < 0 || bounces > RenderSettings::kMaxBounces)
    throw RequestError("bounces",
                       "must be from 0 to " + std::to_string(RenderSettings::kMaxBounces));
  s.bounces = bounces;
  return s;
}

void SamplingRequest::checkWork(double width, double height, double passes) const {
  checkTimeEstimate(width * height * double(spp) * passes, threads, "spp", std::to_string(spp),
                    "use fewer samples");
}

ViewFilter FilterRequest::filter() const {
  ViewFilter filter;
  if (!parseViewFilterKind(kind, filter.kind))
    throw RequestError("filter",
                       "expected none, view, tent, gaussian or period, got '" + kind + "'");
  if (!(widthViews >= 0.05 && widthViews <= 20))
    throw RequestError("filter_width", "expected a width in views between 0.05 and 20, got " +
                                           std::to_string(widthViews));
  filter.widthViews = widthViews;
  return filter;
}

void FramingRequest::check() const {
  DisplayPlacement probe;
  apply(probe);
}

void setFramingFigures(JsonWriter& json, const std::string& at, const Framing& f) {
  json.set(at + "/fit", displayFitName(f.fit));
  json.set(at + "/focus_mm", f.focusMm);
  json.set(at + "/depth_budget_mm", f.budgetMm);
  json.set(at + "/depth_of_field_mm", f.depthOfFieldMm);
  json.set(at + "/depth_scale", f.depthScale);
  if (f.lenticular) {
    json.set(at + "/virtual_depth_of_field_mm", f.depthOfFieldMm / f.depthScale);
  } else {
    json.set(at + "/gap_mm", f.gapMm);
    json.set(at + "/virtual_gap_mm", f.virtualGapMm);
    json.set(at + "/virtual_depth_of_field_mm", f.depthOfFieldMm * f.virtualGapMm / f.gapMm);
  }
  if (!f.hasContent) return;
  json.set(at + "/content_near_mm", f.nearMm);
  json.set(at + "/content_far_mm", f.farMm);
  json.set(at + "/shown_near_mm", f.shownNearMm);
  json.set(at + "/shown_far_mm", f.shownFarMm);
  json.set(at + "/within_budget", f.withinBudget());
}

void recordFraming(JsonWriter& record, const Framing& f) {
  record.set("/framing/fit", displayFitName(f.fit));
  if (f.focusAuto)
    record.set("/framing/focus", "auto");
  else
    record.set("/framing/focus", f.focusMm);
  if (f.budgetAuto)
    record.set("/framing/depth_budget", "auto");
  else
    record.set("/framing/depth_budget", f.budgetMm);
  setFramingFigures(record, "/framing", f);
  if (!f.lenticular) record.set("/framing/virtual_gap_from_display_file", f.virtualGapFixed);
  record.set("/framing/scale_mm_per_unit", f.scaleMmPerUnit);
}

}  // namespace parallax::jobs
