#include "parallax/jobs/video_output.h"

#include <cstdio>
#include <filesystem>

#include "parallax/core/error.h"
#include "parallax/io/image_file.h"

namespace parallax::jobs {

void checkVideoRequest(const VideoRequest& o) {
  if (o.wanted()) checkVideoOptions(o.file, o.videoOptions());
}

void checkVideoFrames(const VideoRequest& o, int width, int height) {
  if (o.wanted()) checkVideoSize(o.file, width, height, o.videoOptions());
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
  if (!writer_.isOpen()) throw RequestError("video", "no frames to write", options_.file);
  writer_.finish();
  return videoSummary(writer_, width_, height_);
}

void writeVideo(const std::vector<std::string>& pngPaths, const VideoRequest& options,
                Reporter& reporter) {
  checkVideoRequest(options);
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
  reporter.result(video.finish());
}

}  // namespace parallax::jobs
