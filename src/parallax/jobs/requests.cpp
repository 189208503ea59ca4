#include "parallax/jobs/requests.h"

#include <charconv>
#include <cmath>
#include <thread>

#include "parallax/accel/accelerator.h"
#include "parallax/cluster/process_group.h"
#include "parallax/core/error.h"
#include "parallax/importer/assimp_importer.h"
#include "parallax/io/rgbd_file.h"
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

// A finite number filling all of `text`, or false.
bool parseNumber(const std::string& text, double& value) {
  const char* end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && stop == end && std::isfinite(value);
}

}  // namespace

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

RgbdOptions RgbdRequest::options() const {
  RgbdOptions o;
  if (convention == "disparity")
    o.convention = DepthConvention::Disparity;
  else if (convention == "depth")
    o.convention = DepthConvention::Depth;
  else if (convention == "inverse")
    o.convention = DepthConvention::Inverse;
  else
    throw RequestError("depth_convention",
                       "expected disparity, depth or inverse, got '" + convention + "'");

  const size_t colon = range.find(':');
  double nearZ = 0, farZ = 0;
  if (colon == std::string::npos || !parseNumber(range.substr(0, colon), nearZ) ||
      !parseNumber(range.substr(colon + 1), farZ))
    throw RequestError("depth_range",
                       "expected NEAR:FAR (two numbers, scene units), got '" + range + "'");
  if (!(nearZ > 0 && farZ > nearZ && farZ <= 1e6 * nearZ))
    throw RequestError("depth_range", "needs 0 < NEAR < FAR <= 1e6 NEAR, got '" + range + "'");
  o.nearDistance = float(nearZ);
  o.farDistance = float(farZ);

  if (edges == "stretch")
    o.edges = RgbdEdges::Stretch;
  else if (edges == "layered")
    o.edges = RgbdEdges::Layered;
  else
    throw RequestError("rgbd_edges", "expected stretch or layered, got '" + edges + "'");

  if (!(fovDegrees >= 1.0 && fovDegrees <= 170.0))
    throw RequestError(
        "rgbd_fov", "must be a number of degrees in [1, 170], got " + std::to_string(fovDegrees));
  o.fovDegrees = float(fovDegrees);
  return o;
}

namespace {

Scene loadRgbd(const RgbdRequest& request) {
  if (request.files.size() != 2) throw RequestError("rgbd", "expected two files: COLOUR DEPTH");
  const RgbdOptions rgbd = request.options();
  try {
    return loadRgbdScene(request.files[0], request.files[1], rgbd, memoryLimitBytes());
  } catch (const InputError& e) {
    // The loader names the file; the field that gave it is rgbd. InputError's text is
    // "file: message" when it has no key.
    if (!e.path().empty()) throw;
    std::string message = e.what();
    const std::string prefix = e.file() + ": ";
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    throw InputError(e.file(), "{rgbd}", message);
  }
}

// --exposure and --view-transform over the scene's own look.
void applyLookOptions(const SceneLoadOptions& load, Scene& scene) {
  if (load.exposureStops) {
    if (!(std::abs(*load.exposureStops) <= 20))
      throw RequestError("exposure", "expected stops in [-20, 20]");
    scene.look.exposureStops = *load.exposureStops;
  }
  if (!load.viewTransform.empty()) {
    const auto transform = parseViewTransform(load.viewTransform);
    if (!transform)
      throw RequestError("view_transform",
                         "unknown view transform '" + load.viewTransform + "' (standard or filmic)",
                         load.viewTransform);
    scene.look.transform = *transform;
  }
}

}  // namespace

Scene loadSceneQuietly(const SceneRequest& request) {
  applyImporterLimits();
  if (!request.rgbd.given() && request.path.empty() && !request.load.camera.empty())
    throw RequestError("camera", "the built-in scene has no cameras");
  Scene scene = request.rgbd.given()   ? loadRgbd(request.rgbd)
                : request.path.empty() ? defaultScene()
                                       : loadScene(request.path, request.load);
  if (request.path.empty() && !request.load.focusOn.empty())
    focusOnObject(scene, request.load.focusOn);
  applyLookOptions(request.load, scene);
  return scene;
}

Scene loadScene(const SceneRequest& request, Reporter& reporter) {
  cluster::failIfAskedForTest(cluster::world());
  Scene scene = loadSceneQuietly(request);
  // Under mpirun every rank loads the scene: its notes once.
  if (!cluster::world().isRoot()) return scene;
  for (const auto& n : scene.notes) reporter.note(n);
  for (const auto& w : scene.warnings) reporter.warning(w);
  return scene;
}

void recordRgbd(JsonWriter& record, const RgbdRequest& request, const Scene& scene) {
  const RgbdOptions o = request.options();
  if (request.files.size() == 2) {
    record.set("/rgbd/colour", request.files[0]);
    record.set("/rgbd/depth", request.files[1]);
  }
  record.set("/rgbd/convention", depthConventionName(o.convention));
  record.set("/rgbd/near", double(o.nearDistance));
  record.set("/rgbd/far", double(o.farDistance));
  record.set("/rgbd/fov_degrees", double(o.fovDegrees));
  record.set("/rgbd/edges", rgbdEdgesName(o.edges));
  if (o.edges == RgbdEdges::Layered) {
    record.set("/rgbd/edge_jump", double(o.edgeJump));
    record.set("/rgbd/background_offset", double(o.backgroundOffset));
  }
  if (!scene.images.empty()) {
    const Image& photo = scene.images[0];
    record.set("/rgbd/width_px", photo.width());
    record.set("/rgbd/height_px", photo.height());
    if (o.edges == RgbdEdges::Layered)
      record.set("/rgbd/background_radius_px", backgroundRadiusPx(o, photo.width()));
  }
  record.set("/rgbd/triangles", uint64_t(scene.triangleCount()));
}

void recordScene(JsonWriter& record, const SceneRequest& request, const Scene& scene) {
  record.set("/scene", scene.source);
  // The look every picture of the render got; simulate's ideal views take it from here.
  if (!scene.look.identity()) {
    record.set("/look/exposure", scene.look.exposureStops);
    record.set("/look/view_transform", viewTransformName(scene.look.transform));
  }
  if (request.rgbd.given()) recordRgbd(record, request.rgbd, scene);
  if (!request.load.camera.empty()) record.set("/scene_camera", request.load.camera);
  if (!request.load.focusOn.empty()) record.set("/scene_focus_on", request.load.focusOn);
}

}  // namespace parallax::jobs
