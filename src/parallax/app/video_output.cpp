#include "parallax/app/video_output.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "parallax/app/cli_support.h"
#include "parallax/core/error.h"
#include "parallax/io/image_file.h"

namespace parallax::app {

void addVideoOptions(CLI::App& cmd, VideoCliOptions& o, const std::string& frames, bool withFps) {
  cmd.add_option("--video", o.file,
                 "Also write " + frames +
                     " as a video: .mp4 (H.264; H.265 above 4096 a side), .webm (VP9) or .mkv "
                     "(docs/video.md)")
      ->type_name("FILE");
  cmd.add_option("--video-codec", o.codec, "Codec of --video: auto, h264, h265 or vp9")
      ->capture_default_str();
  cmd.add_option("--video-quality", o.quality,
                 "Constant quality (CRF) of --video, lower is better: 0 to 51 for h264 and h265 "
                 "(18: visually lossless), 0 to 63 for vp9")
      ->capture_default_str()
      ->check(integerIn(0, 63));
  if (!withFps) return;
  cmd.add_option("--fps", o.fps, "Frames per second of --video, above 0 and at most 240")
      ->capture_default_str()
      ->check(realIn(0, 240, Bound::Open));
}

void checkVideoCliOptions(const VideoCliOptions& o) {
  if (o.wanted()) checkVideoOptions(o.file, o.videoOptions());
}

std::string videoSummary(const VideoWriter& writer, int width, int height) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(writer.path(), ec);
  char line[512];
  std::snprintf(line, sizeof line, "wrote %s: %d frames, %dx%d (coded %dx%d), %s, %llu bytes",
                writer.path().c_str(), writer.frames(), width, height, writer.codedWidth(),
                writer.codedHeight(), writer.codec().c_str(),
                static_cast<unsigned long long>(ec ? 0 : bytes));
  return line;
}

void VideoOutput::add(const Image& picture) {
  if (!writer_.isOpen()) {
    width_ = picture.width();
    height_ = picture.height();
    writer_.open(options_.file, width_, height_, options_.videoOptions());
  }
  writer_.addFrame(picture);
}

std::string VideoOutput::finish() {
  if (!writer_.isOpen()) throw InputError("--video", options_.file, "no frames to write");
  writer_.finish();
  return videoSummary(writer_, width_, height_);
}

void writeVideo(const std::vector<std::string>& pngPaths, const VideoCliOptions& options) {
  checkVideoCliOptions(options);
  VideoOutput video(options);
  int width = 0, height = 0;
  for (const std::string& path : pngPaths) {
    const Image picture = readImage(path);
    if (width == 0) {
      width = picture.width();
      height = picture.height();
    } else if (picture.width() != width || picture.height() != height) {
      throw InputError(path, "",
                       "is " + std::to_string(picture.width()) + "x" +
                           std::to_string(picture.height()) + ", the video's first frame " +
                           std::to_string(width) + "x" + std::to_string(height));
    }
    video.add(picture);
  }
  std::printf("%s\n", video.finish().c_str());
}

}  // namespace parallax::app
