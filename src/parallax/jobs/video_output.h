// A video request (video, video_codec, video_quality, fps) for commands that make a sequence of
// pictures (the eye sweep of `parallax simulate`): the pictures become one video file
// (video/video_writer.h, docs/video.md).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "parallax/image/image.h"
#include "parallax/jobs/reporter.h"
#include "parallax/video/video_writer.h"

namespace parallax::jobs {

struct VideoRequest {
  std::string file;  // empty: no video
  std::string codec = "auto";
  int quality = 23;
  double fps = 30;

  bool wanted() const { return !file.empty(); }
  VideoOptions videoOptions() const { return {codec, quality, fps}; }
};

// Refuses bad video options (InputError naming the option) before any work is done.
void checkVideoRequest(const VideoRequest& o);

// checkVideoRequest and the encoder's limits for frames of width x height (checkVideoSize), before
// the frames are made.
void checkVideoFrames(const VideoRequest& o, int width, int height);

// One line for the user: "wrote FILE: N frames, WxH (coded WxH), CODEC, B bytes".
std::string videoSummary(const VideoWriter& writer, int width, int height);

// A video written frame by frame as a command makes its pictures: opened on the first picture
// (its size is the video's), moved into place by finish(); dropped without finish(), it leaves
// no file.
class VideoOutput {
 public:
  explicit VideoOutput(VideoRequest options) : options_(std::move(options)) {}
  void add(const Image& picture);
  // Finishes the file and returns videoSummary()'s line.
  std::string finish();
  const VideoWriter& writer() const { return writer_; }

 private:
  VideoRequest options_;
  VideoWriter writer_;
  int width_ = 0, height_ = 0;
};

// Reads the pictures (io/image_file.h: PNG, JPEG or PFM; all of one size), encodes them in
// order and prints videoSummary()'s line. Throws InputError naming a picture that cannot be read
// or has another size than the first.
void writeVideo(const std::vector<std::string>& pngPaths, const VideoRequest& options,
                Reporter& reporter = silentReporter());

}  // namespace parallax::jobs
