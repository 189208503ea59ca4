// A quilt picture or quilt video played on a lenticular panel (`parallax show QUILT --display
// lkg:NAME`, docs/quilts.md "Playing a quilt"): each frame interlaced as it is shown by one
// table made once (render/quilt.h, QuiltInterlacer: the picture `parallax interlace` makes, to
// within one code), a video decoded as it plays (FFmpeg, video/video_writer.h) on a thread of
// its own, a few frames ahead of the screen.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "parallax/jobs/display_request.h"
#include "parallax/jobs/reporter.h"

namespace parallax::jobs {

struct QuiltPlayRequest {
  // A quilt picture (NAME_qs{C}x{R}a{aspect}.png, .jpg) or video (.mp4, .webm, .mkv, .mov):
  // its layout from its name as Looking Glass's tools write it.
  std::string quilt;
  // A lenticular panel: its calibration file or lkg:NAME, and the lens reading (its optics).
  DisplayRequest display;
  std::string viewResampling = "linear";  // view_resampling: nearest or linear
  // What the caller holds beside the player at its peak (its windows): in the memory estimate.
  double otherBytesPerPanelPixel = 0, otherBytes = 0;
};

// Whether `path` names a video by its extension (.mp4, .webm, .mkv, .mov, .avi).
bool isVideoPath(const std::string& path);

class QuiltPlayer {
 public:
  // Reads and checks everything before anything is shown: the panel (lenticular only), the
  // quilt's name and size, a video's every frame (decoded once: its frame count and rate), and
  // the memory estimate. Throws InputError or RequestError naming the file or the field.
  QuiltPlayer(const QuiltPlayRequest& request, Reporter& reporter);
  ~QuiltPlayer();  // stops the decoding thread
  QuiltPlayer(const QuiltPlayer&) = delete;
  QuiltPlayer& operator=(const QuiltPlayer&) = delete;

  int width() const;  // the panel's pixels
  int height() const;
  bool isVideo() const;
  double fps() const;  // a video's frame rate (0 for a picture)
  int frames() const;  // a video's frames (1 for a picture)

  // The next panel frame (RGB codes, width x height, row 0 at the top); a video starts again
  // after its last frame. Rethrows what the decoding thread met.
  bool next(std::vector<uint8_t>& rgb);

  // Since the start: the frames made, the seconds spent decoding (FFmpeg and its conversion to
  // RGB) and interlacing them (the thread's work, not its waits).
  struct Timing {
    long frames = 0;
    double decodeSeconds = 0, interlaceSeconds = 0;
  };
  Timing timing() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace parallax::jobs
