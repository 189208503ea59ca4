#include "parallax/jobs/sequence.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "parallax/cluster/process_group.h"
#include "parallax/core/error.h"
#include "parallax/io/json_reader.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/reporter.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/scene_request.h"

namespace parallax::jobs {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

constexpr int kMaxFrames = 1000000;
constexpr double kDefaultTurntableSeconds = 4.0;

}  // namespace

void parseFrameRange(const std::string& text, int total, int& first, int& last) {
  const auto fail = [&](const std::string& why) {
    throw RequestError("frames", why + ", got '" + text + "'");
  };
  const size_t colon = text.find(':');
  const std::string a = text.substr(0, colon);
  const std::string b = colon == std::string::npos ? a : text.substr(colon + 1);
  const auto number = [&](const std::string& s) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos)
      fail("expected FIRST:LAST frame numbers from 1");
    return std::stoi(s);
  };
  first = number(a);
  last = number(b);
  if (first < 1 || last < first) fail("expected 1 <= FIRST <= LAST");
  if (last > total)
    fail("the animation has " + std::to_string(total) + " frame" + (total == 1 ? "" : "s"));
}

void narrowToChunk(const std::string& text, int& first, int& last) {
  const size_t slash = text.find('/');
  const auto number = [&](const std::string& digits) {
    if (digits.empty() || digits.size() > 6 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
      throw RequestError("chunk",
                         "expected K/N, the K-th of N parts (1 <= K <= N), got '" + text + "'");
    return std::stoi(digits);
  };
  const int k = number(text.substr(0, slash));
  const int n = slash == std::string::npos ? 0 : number(text.substr(slash + 1));
  if (n < 1 || k < 1 || k > n)
    throw RequestError("chunk", "expected K/N with 1 <= K <= N, got '" + text + "'");
  const int64_t count = last - first + 1;
  const int start = first;
  first = start + int(count * (k - 1) / n);
  last = start + int(count * k / n) - 1;
}

std::string numberedPicture(const std::string& path, int frame) {
  const std::filesystem::path p(path);
  const std::string name = frameName(frame);  // "frame-0007": the number after the dash
  return (p.parent_path() /
          (p.stem().string() + name.substr(name.find('-')) + p.extension().string()))
      .string();
}

VideoRequest SequenceRequest::videoOptions() const {
  VideoRequest o = video;
  o.fps = fps;
  if (o.wanted() && !chunk.empty())
    throw RequestError("video",
                       "{chunk} renders one part of the frames: make the video in a final step, "
                       "the same command without {chunk} (docs/distributed.md)");
  checkVideoRequest(o);
  return o;
}

void adoptAnimation(SequenceRequest& options, const Scene& scene) {
  if (!options.video.wanted() || options.given()) return;
  if (sceneMotion(scene).keyedSeconds() <= 0)
    throw RequestError("video",
                       "makes a video of a sequence, and the scene has no animation: add "
                       "{turntable} DEGREES (or animation keys in a scene file)");
  options.wholeAnimation = true;
}

void writeSequenceVideo(const SequenceRequest& options, const SequencePlan& plan,
                        const std::function<std::string(int frame)>& picture, Reporter& reporter) {
  const VideoRequest video = options.videoOptions();
  if (!video.wanted() || !cluster::world().isRoot()) return;  // after runSequence's last checkpoint
  std::vector<std::string> pictures;
  for (int frame = plan.first; frame <= plan.last; ++frame) pictures.push_back(picture(frame));
  writeVideo(pictures, video, reporter);
}

SequencePlan planSequence(const SequenceRequest& options, const Scene& scene) {
  SequencePlan plan;
  plan.motion = sceneMotion(scene);
  plan.fps = options.fps;
  const double keyed = plan.motion.keyedSeconds();
  plan.seconds = options.duration > 0     ? options.duration
                 : keyed > 0              ? keyed
                 : options.turntable != 0 ? kDefaultTurntableSeconds
                                          : 0.0;
  if (options.turntable != 0)
    plan.motion.turntable = contentTurntable(scene, options.turntable / plan.seconds);
  // A turntable's frames cover [0, seconds): the last frame's turn plus one step is the whole
  // turn, so a 360-degree sequence loops. Keys' frames include the last key.
  const double frames = options.turntable != 0 ? plan.seconds * plan.fps
                                               : std::floor(plan.seconds * plan.fps + 1e-9) + 1;
  if (!(frames <= kMaxFrames))
    throw RequestError(options.duration > 0 ? "duration" : "fps",
                       "the animation would have " + std::to_string(std::lround(frames)) +
                           " frames; at most " + std::to_string(kMaxFrames));
  plan.total = std::max(1, int(std::lround(frames)));
  plan.first = 1;
  plan.last = plan.total;
  if (!options.frames.empty()) parseFrameRange(options.frames, plan.total, plan.first, plan.last);
  if (!options.chunk.empty()) narrowToChunk(options.chunk, plan.first, plan.last);
  return plan;
}

std::vector<double> SequencePlan::times() const {
  std::vector<double> t(static_cast<size_t>(total));
  for (int k = 1; k <= total; ++k) t[size_t(k - 1)] = timeOf(k);
  return t;
}

void noteAnimation(const SequenceRequest& options, const Scene& scene, Reporter& reporter) {
  if (!cluster::world().isRoot()) return;
  if (options.wholeAnimation) {
    const SequencePlan plan = planSequence(options, scene);
    reporter.note(printed("the scene is animated (%g s): {video} makes all %d frames at %g fps",
                          plan.seconds, plan.total, plan.fps));
    return;
  }
  if (options.given()) return;
  const SceneMotion motion = sceneMotion(scene);
  if (motion.empty()) return;
  const SequencePlan plan = planSequence(options, scene);
  reporter.note(printed(
      "the scene is animated (%g s, %d frames at %g fps); this is its rest pose: {frames} 1:%d "
      "renders the frames (docs/animation.md)",
      plan.seconds, plan.total, plan.fps, plan.total));
}

std::string frameName(int frame) {
  char text[32];
  std::snprintf(text, sizeof text, "frame-%04d", frame);
  return text;
}

void prepareFraming(Scene& scene, const SequencePlan& plan) {
  encloseMotion(scene, plan.motion, plan.times());
}

void recordSequence(JsonWriter& record, const SequencePlan& plan, int frame) {
  record.set("/sequence/frame", frame);
  record.set("/sequence/seconds", plan.timeOf(frame));
  record.set("/sequence/first", plan.first);
  record.set("/sequence/last", plan.last);
  record.set("/sequence/frames", plan.total);
  record.set("/sequence/fps", plan.fps);
  record.set("/sequence/duration", plan.seconds);
  if (plan.motion.turntable) {
    const Turntable& t = *plan.motion.turntable;
    record.set("/sequence/turntable/degrees_per_second", t.degreesPerSecond);
    record.set("/sequence/turntable/pivot", t.pivot);
    record.set("/sequence/turntable/axis", t.axis);
  }
  record.set("/sequence/camera_keys", int(plan.motion.cameraKeys.size()));
  record.set("/sequence/display_keys", int(plan.motion.displayKeys.size()));
}

namespace {

// The placement's axes: right, up, toward the viewer.
void placementAxes(const DisplayPlacement& d, Vec3f axes[3]) {
  axes[2] = normalize(d.normal);
  axes[1] = normalize(d.up - axes[2] * dot(d.up, axes[2]));
  axes[0] = cross(axes[1], axes[2]);
}

}  // namespace

void runSequence(const SequencePlan& plan, const Scene& framed, const FrameJob& job) {
  // Under mpirun each rank takes every size-th unfinished frame (round robin: neighbouring
  // frames cost about the same, so the ranks' shares do too), loads and builds once, and all
  // meet before the first frame is written and after the last (docs/distributed.md).
  cluster::ProcessGroup& group = cluster::world();
  std::vector<int> todo;
  for (int frame = plan.first; frame <= plan.last; ++frame)
    if (!job.finished(frame)) todo.push_back(frame);
  const int done = plan.count() - int(todo.size());
  if (group.isRoot())
    job.reporter->result(printed(
        "sequence: frames %d to %d of %d at %g fps, %d to render%s%s", plan.first, plan.last,
        plan.total, plan.fps, int(todo.size()),
        done ? (", " + std::to_string(done) + " finished before").c_str() : "",
        group.size() > 1 ? (" by " + std::to_string(group.size()) + " ranks").c_str() : ""));
  std::vector<int> mine;
  for (size_t i = 0; i < todo.size(); ++i)
    if (int(i % size_t(group.size())) == group.rank()) mine.push_back(todo[i]);
  if (mine.empty()) {
    group.checkpoint();  // every rank has seen which frames were finished before
    group.checkpoint();  // every frame is written
    return;
  }
  // The framing's centre in the first key's axes, carried to each frame's axes.
  Vec3f framingOffset{0.0f};
  if (!plan.motion.displayKeys.empty()) {
    const DisplayKey first = displayAt(plan.motion.displayKeys, 0.0);
    Vec3f axes[3];
    placementAxes(framed.display, axes);
    const Vec3f shift = framed.display.center - first.center;
    framingOffset = Vec3f(dot(shift, axes[0]), dot(shift, axes[1]), dot(shift, axes[2]));
  }
  Scene posed = framed;
  const auto pose = [&](int frame) {
    poseScene(framed, plan.motion, plan.timeOf(frame), posed);
    if (plan.motion.displayKeys.empty()) return;
    Vec3f axes[3];
    placementAxes(posed.display, axes);
    posed.display.center = posed.display.center + axes[0] * framingOffset.x +
                           axes[1] * framingOffset.y + axes[2] * framingOffset.z;
  };
  pose(mine.front());
  AcceleratorOptions options = job.accelerator;
  options.dynamic = plan.motion.movesGeometry();
  const auto buildStart = std::chrono::steady_clock::now();
  Accelerator accelerator(posed, options);
  const double buildSeconds = secondsSince(buildStart);
  group.checkpoint();  // every rank has loaded, built, and seen which frames were finished
  double refitSeconds = 0;
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < mine.size(); ++i) {
    const int frame = mine[i];
    if (i > 0) {
      pose(frame);
      if (plan.motion.movesGeometry()) {
        const auto refitStart = std::chrono::steady_clock::now();
        accelerator.refit(posed);
        refitSeconds += secondsSince(refitStart);
      }
    }
    if (group.size() > 1)
      job.reporter->result(printed("frame %d (rank %d: %zu of %zu, t = %.3f s)", frame,
                                   group.rank(), i + 1, mine.size(), plan.timeOf(frame)));
    else
      job.reporter->result(printed("frame %d (%zu of %zu, t = %.3f s)", frame, i + 1, mine.size(),
                                   plan.timeOf(frame)));
    job.render(posed, accelerator, frame);
  }
  const double seconds = secondsSince(start);
  job.reporter->result(
      printed("sequence: %zu frames in %.2f s (%.2f s a frame; BVH built once in %.3f s, "
              "refitted in %.4f s a frame)",
              mine.size(), seconds, seconds / double(mine.size()), buildSeconds,
              mine.size() > 1 ? refitSeconds / double(mine.size() - 1) : 0.0));
  group.checkpoint();  // every frame is written
}

void addFileContent(MadeFrom& made, const std::string& path) {
  std::error_code ec;
  if (path.empty() || !std::filesystem::is_regular_file(path, ec)) return;
  std::ifstream in(path, std::ios::binary);
  uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bits
  char buffer[65536];
  while (in) {
    in.read(buffer, sizeof buffer);
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      hash ^= uint8_t(buffer[i]);
      hash *= 1099511628211ull;
    }
  }
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  made.emplace_back("content of " + path, text);
}

std::string madeFromNumber(double value) {
  return printed("%.10g", value);
}

MadeFrom sceneMadeFrom(const SceneRequest& request, const Scene& scene) {
  MadeFrom made{{"version", PARALLAX_VERSION},
                {"scene", request.path.empty() ? "<built-in>" : request.path},
                {"{camera}", request.load.camera},
                {"{focus_on}", request.load.focusOn},
                {"{mesh_up}", upAxisName(request.load.import.up)},
                {"{crease}", madeFromNumber(request.load.import.creaseDegrees)}};
  const RgbdRequest& rgbd = request.rgbd;
  if (rgbd.given()) {
    std::string files;
    for (const std::string& file : rgbd.files) files += (files.empty() ? "" : " ") + file;
    made.insert(made.end(), {{"{rgbd}", files},
                             {"{depth_convention}", rgbd.convention},
                             {"{depth_range}", rgbd.range},
                             {"{rgbd_edges}", rgbd.edges},
                             {"{rgbd_fov}", madeFromNumber(rgbd.fovDegrees)}});
    for (const std::string& file : rgbd.files) addFileContent(made, file);
  }
  addFileContent(made, request.path);
  for (const Scene::ImportRecord& import : scene.imports)
    if (import.file != request.path) addFileContent(made, import.file);
  return made;
}

void addSamplingMadeFrom(MadeFrom& made, const SamplingRequest& s) {
  made.insert(made.end(), {{"{spp}", std::to_string(s.spp)},
                           {"{seed}", std::to_string(s.seed)},
                           {"{jitter}", s.jitter},
                           {"{adaptive}", s.adaptive ? "on" : "off"},
                           {"{adaptive_threshold}", madeFromNumber(s.adaptiveThreshold)},
                           {"{bounces}", std::to_string(s.bounces)}});
}

void addSequenceMadeFrom(MadeFrom& made, const SequenceRequest& sequence) {
  made.insert(made.end(), {{"{turntable}", madeFromNumber(sequence.turntable)},
                           {"{duration}", madeFromNumber(sequence.duration)},
                           {"{fps}", madeFromNumber(sequence.fps)}});
}

void recordMadeFrom(JsonWriter& record, const MadeFrom& made) {
  for (size_t i = 0; i < made.size(); ++i) {
    record.set("/made_from/" + std::to_string(i) + "/setting", made[i].first);
    record.set("/made_from/" + std::to_string(i) + "/value", made[i].second);
  }
}

void checkMadeFrom(const std::string& recordFile, const std::string& finished, const MadeFrom& made,
                   const std::string& startOver) {
  const std::string howToStart =
      "; the frames of one sequence must match: give another {output}, or remove " + startOver +
      " to start over";
  std::map<std::string, std::string> before;
  bool recorded = false;
  try {
    const JsonDocument document = JsonDocument::parseFile(recordFile);
    if (const auto list = document.root().find("made_from")) {
      recorded = true;
      for (const JsonReader& entry : list->elements())
        before[entry["setting"].string()] = entry["value"].string();
    }
  } catch (const InputError&) {
    recorded = false;
  }
  if (!recorded)
    throw InputError(finished, "",
                     "is a finished frame without a record of its settings (an earlier parallax, "
                     "or a damaged record)" +
                         howToStart);
  for (const auto& [setting, value] : made) {
    const auto was = before.find(setting);
    if (was != before.end() && was->second == value) continue;
    if (setting.rfind("content of ", 0) == 0)
      throw InputError(finished, "",
                       was == before.end()
                           ? "was not made from " + setting.substr(11) + howToStart
                           : "was made from another version of " + setting.substr(11) +
                                 " (the file has changed since)" + howToStart);
    throw InputError(finished, "",
                     setting + ": it was made with " +
                         (was == before.end() ? std::string("another setting") : was->second) +
                         ", this run asks " + value + howToStart);
  }
  for (const auto& [setting, value] : before) {
    bool asked = false;
    for (const auto& entry : made) asked = asked || entry.first == setting;
    if (!asked)
      throw InputError(
          finished, "",
          setting.rfind("content of ", 0) == 0
              ? "was made from " + setting.substr(11) + ", this run does not use it" + howToStart
              : setting + ": it was made with " + value + ", this run has none" + howToStart);
  }
}

}  // namespace parallax::jobs
