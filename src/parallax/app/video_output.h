// `--video FILE` and its options for commands that make a sequence of pictures (the eye sweep of
// `parallax simulate`): the pictures become one video file (video/video_writer.h,
// docs/video.md).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "parallax/image/image.h"
#include "parallax/video/video_writer.h"

namespace CLI {
class App;
}  // namespace CLI

namespace parallax::app {

struct VideoCliOptions {
  std::string file;  // empty: no video
  std::string codec = "auto";
  int quality = 23;
  double fps = 30;

  bool wanted() const { return !file.empty(); }
  VideoOptions videoOptions() const { return {codec, quality, fps}; }
};

// Adds --video, --video-codec, --video-quality and (unless the command's sequence options
// already have it: `withFps` false) --fps to `cmd`; `o` must outlive it (keep it in the
// command's shared options). `frames` says what the frames are, for the help text.
void addVideoOptions(CLI::App& cmd, VideoCliOptions& o, const std::string& frames,
                     bool withFps = true);
// Refuses bad video options (InputError naming the option) before any work is done.
void checkVideoCliOptions(const VideoCliOptions& o);

// One line for the user: "wrote FILE: N frames, WxH (coded WxH), CODEC, B bytes".
std::string videoSummary(const VideoWriter& writer, int width, int height);

// A video written frame by frame as a command makes its pictures: opened on the first picture
// (its size is the video's), moved into place by finish(); dropped without finish(), it leaves
// no file.
class VideoOutput {
 public:
  explicit VideoOutput(VideoCliOptions options) : options_(std::move(options)) {}
  void add(const Image& picture);
  // Finishes the file and returns videoSummary()'s line.
  std::string finish();
  const VideoWriter& writer() const { return writer_; }

 private:
  VideoCliOptions options_;
  VideoWriter writer_;
  int width_ = 0, height_ = 0;
};

// Reads the pictures (io/image_file.h: PNG, JPEG or PFM; all of one size), encodes them in
// order and prints videoSummary()'s line. Throws InputError naming a picture that cannot be read
// or has another size than the first.
void writeVideo(const std::vector<std::string>& pngPaths, const VideoCliOptions& options);

}  // namespace parallax::app
