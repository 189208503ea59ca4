// Frame sequences for `render` (layers and quilts) and `view` (docs/animation.md): frames,
// turntable, duration and fps, the plan they make, and the folder of finished frames.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/jobs/reporter.h"
#include "parallax/jobs/video_output.h"

#include "parallax/scene/motion.h"
#include "parallax/scene/scene.h"

namespace parallax {
class JsonWriter;
}

namespace parallax::jobs {

struct SamplingRequest;
struct SceneRequest;

struct SequenceRequest {
  VideoRequest video;    // --video FILE: the frames as one video, at --fps
  std::string frames;    // "A:B", 1-based and inclusive; "" = every frame of the animation
  std::string chunk;     // "K/N": only the K-th of N contiguous parts of the frames (a farm task)
  double turntable = 0;  // degrees the content turns over the whole animation; 0 = none
  double duration = 0;   // seconds of the animation; 0 = the keys' last time, else 4 s
  double fps = 30;
  // Set by adoptAnimation: --video of an animated scene without a range makes every frame.
  bool wholeAnimation = false;
  // A sequence was asked for (else the command renders one picture, at time 0).
  bool given() const {
    return !frames.empty() || !chunk.empty() || turntable != 0 || wholeAnimation;
  }
  // --video's options at the sequence's --fps; refuses a video without a sequence.
  VideoRequest videoOptions() const;
};

// The animation's frames: frame k (1-based) shows time (k - 1) / fps. A 360-degree turntable
// over N frames thus loops: frame N + 1 would be frame 1 again.
struct SequencePlan {
  SceneMotion motion;
  double fps = 30;
  double seconds = 0;  // the animation's length
  int total = 1;       // frames of the whole animation
  int first = 1, last = 1;
  // Every frame's time, of the whole animation (not only first..last): what the framing
  // measures, so that a range rendered apart frames the content exactly as the whole does.
  std::vector<double> times() const;
  double timeOf(int frame) const { return (frame - 1) / fps; }
  int count() const { return last - first + 1; }
};

// --video without --frames, --chunk or --turntable: the scene's own animation, every frame
// (as Blender renders an animation's frame range); a scene without one is refused (RequestError
// naming --video). Nothing for any other request. Call it once the scene is loaded, before
// the outputs are checked.
void adoptAnimation(SequenceRequest& options, const Scene& scene);

// The plan for `scene` (its keys) and the options; throws InputError naming --frames,
// --turntable, --duration or --fps. A turntable lasts `duration` (default 4 s) and turns the
// content (contentTurntable) by `turntable` degrees over it; keys last until their last time.
SequencePlan planSequence(const SequenceRequest& options, const Scene& scene);

// Without a sequence asked for, one line on stderr when the scene moves (keys or a glTF
// animation): how to render its frames.
void noteAnimation(const SequenceRequest& options, const Scene& scene, Reporter& reporter);

// After a sequence: the plan's frames (finished now, whether in this run or before) as the
// video --video asks for; `picture(frame)` is the path of a frame's picture.
void writeSequenceVideo(const SequenceRequest& options, const SequencePlan& plan,
                        const std::function<std::string(int frame)>& picture, Reporter& reporter);

// "A:B" (or "A") -> [A, B] within [1, total]; throws InputError naming --frames.
void parseFrameRange(const std::string& text, int total, int& first, int& last);

// "K/N" -> [first, last] narrowed to the K-th of N contiguous parts, as equal as can be (the
// first parts one frame shorter); a part may be empty (last = first - 1) when N exceeds the
// frames. Throws InputError naming --chunk.
void narrowToChunk(const std::string& text, int& first, int& last);

// A picture's path with the frame's number before the extension: out/view.png ->
// out/view-0007.png.
std::string numberedPicture(const std::string& path, int frame);

// "frame-0007": the folder (or, with a suffix, the file stem) of one frame, 4 digits at least.
std::string frameName(int frame);

// Before the framing: the display placed at its first key, and the framing's bounds
// (DisplayPlacement::fit and ::content) replaced by their envelope over the whole animation
// (movedBounds), so that one framing holds for every frame and the content does not pump.
void prepareFraming(Scene& scene, const SequencePlan& plan);

// One sequence's work: whether a frame is finished already (its output exists), and how to
// render one posed frame with the accelerator of the whole sequence.
struct FrameJob {
  std::function<bool(int frame)> finished;
  std::function<void(const Scene& posed, const Accelerator& accelerator, int frame)> render;
  AcceleratorOptions accelerator;          // `dynamic` is set when the geometry moves
  Reporter* reporter = &silentReporter();  // one line per frame and a summary
};

// Renders the plan's unfinished frames in order: the scene (framed once, after prepareFraming)
// is posed per frame into one copy and the accelerator, built once, is refitted to it. Display
// keys move the framed placement: the framing's offset of the centre (its zero-parallax plane)
// and its width ride along. Prints one line per frame and a summary.
void runSequence(const SequencePlan& plan, const Scene& framed, const FrameJob& job);

// The sequence's keys in a record: /sequence/{frames, first, last, fps, seconds, turntable...}.
void recordSequence(JsonWriter& record, const SequencePlan& plan, int frame);

// What a sequence's frames are made from, so that a resumed sequence never mixes frames of other
// settings (docs/animation.md, "Resuming"): every setting that changes the pictures, as (label,
// value) pairs in a fixed order. A label is a request field as {field} (spelled by the front
// end), "scene", or "content of FILE" (a hash of the file's bytes).
using MadeFrom = std::vector<std::pair<std::string, std::string>>;

// ("content of PATH", a 64-bit FNV-1a hash of its bytes in hex); nothing for "" or a path that
// is not a readable file (a preset name, the built-in display).
void addFileContent(MadeFrom& made, const std::string& path);

// A number as made-from values write it (10 significant digits).
std::string madeFromNumber(double value);

// The version, the scene (its path, import options, RGB-D photo) and the contents of its files
// (the scene file, the mesh files it imported, the photo).
MadeFrom sceneMadeFrom(const SceneRequest& request, const Scene& scene);
// spp, seed, jitter, adaptive, adaptive_threshold and bounces (not threads: they change no
// picture).
void addSamplingMadeFrom(MadeFrom& made, const SamplingRequest& sampling);
// turntable, duration and fps (not frames and chunk: they choose frames).
void addSequenceMadeFrom(MadeFrom& made, const SequenceRequest& sequence);

// /made_from in a frame's record: [{"setting": label, "value": value}, ...].
void recordMadeFrom(JsonWriter& record, const MadeFrom& made);

// Refuses (InputError naming `finished`, the first setting that differs, what the finished
// frame was made with and what this run asks, and how to start over) a finished frame whose
// record `recordFile` has another /made_from than `made`, or none (an earlier version's). `start
// over` names what to remove to start over.
void checkMadeFrom(const std::string& recordFile, const std::string& finished, const MadeFrom& made,
                   const std::string& startOver);

}  // namespace parallax::jobs
