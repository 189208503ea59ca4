// Video files of pictures: H.264, H.265 (HEVC) and VP9 in MP4, WebM and Matroska, encoded with
// Debian's FFmpeg libraries (docs/video.md). FFmpeg stays in this module's .cpp files; no FFmpeg
// type appears here.
//
// Pictures are encoded as 8-bit sRGB codes converted to YUV 4:2:0 (BT.709 matrix, limited
// range), the one layout every player decodes. 4:2:0 shares one chroma sample between 2 x 2
// pixels, so the coded size is even: an odd width (height) gets one more column (row), a copy
// of the last one, and a decoder returns the coded size (codedWidth(), codedHeight()).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "parallax/image/image.h"

namespace parallax {

struct VideoOptions {
  // "h264", "h265" or "vp9"; "auto": by the extension, .mp4 and .mkv -> h264 (h265 when either
  // side exceeds 4096, H.264's practical limit: level 5.2 decoders, i.e. most hardware, stop at
  // 4096 x 2304), .webm -> vp9.
  std::string codec = "auto";
  // Constant quality (CRF), lower is better: 0 to 51 for h264 and h265 (x264's and x265's
  // scale; 18 looks lossless to most viewers, +6 about halves the size), 0 to 63 for vp9
  // (libvpx's scale). 23 is x264's default.
  int quality = 23;
  // Frames per second, above 0 and at most 240 (stored as the nearest fraction, 29.97 ->
  // 30000/1001).
  double fps = 30;
};

// The request fields that errors name (RequestError::field, core/error.h), so that a front end
// can say which of its options was wrong in its own spelling; the defaults are the request's
// fields. Errors about the file carry its path as the value.
struct VideoFieldNames {
  std::string file = "video";
  std::string codec = "video_codec";
  std::string quality = "video_quality";
  std::string fps = "fps";
};

// The encoder a codec name stands for, after "auto" is resolved for a picture of width x
// height saved at `path`. Throws RequestError for an unknown extension, codec or a codec the
// container does not carry.
std::string resolveVideoCodec(const std::string& path, const VideoOptions& options, int width,
                              int height, const VideoFieldNames& names = {});
// Everything open() checks that does not need the picture size: the extension, the codec's name,
// that Debian's FFmpeg has its encoder, the container, the quality and fps ranges, and that
// `path` is not a folder and its folder exists (or can be made). Lets a command refuse bad options
// before it works for the frames.
// A path whose folder (or nearest existing ancestor) cannot be written is refused too.
void checkVideoOptions(const std::string& path, const VideoOptions& options,
                       const VideoFieldNames& names = {});
// checkVideoOptions and what open() would refuse for frames of width x height: the x264 or x265
// encoder is opened at that size (and closed) without a file, so that a size it refuses is
// known before the frames are rendered; VP9's limit (16384 a side) is checked by name.
void checkVideoSize(const std::string& path, int width, int height, const VideoOptions& options,
                    const VideoFieldNames& names = {});

// Writes frames to a temporary file beside `path` (path + ".partial-<pid>"; those of killed
// runs are removed when the next writer of `path` opens) and renames
// it into place in finish(); a writer destroyed without finish() removes the temporary file, so
// a failed run never leaves a partial video. The output is deterministic: the same frames and
// options give the same bytes (one encoder thread per frame order, no times or versions in the
// file; docs/video.md).
class VideoWriter {
 public:
  VideoWriter();
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // Throws RequestError naming names.file (or the codec, quality, fps field) for a bad path or
  // option, and for a size the encoder refuses.
  void open(const std::string& path, int width, int height, const VideoOptions& options = {},
            const VideoFieldNames& names = {});
  // A picture in linear light (encoded to 8-bit sRGB, image/image.h), of the size given to
  // open(); throws RequestError (names.file) otherwise.
  void addFrame(const Image& image);
  // 8-bit sRGB codes already made (width x height RGB triples, row 0 at the top; a PNG's codes
  // as they are).
  void addFrame8(const uint8_t* rgb, int width, int height);
  // Flushes the encoder, closes the file and renames it into place. Throws RequestError naming
  // the file when no frame was added (and removes the temporary file).
  void finish();

  bool isOpen() const;
  int frames() const;         // frames added so far
  std::string codec() const;  // "h264", "h265" or "vp9"
  int codedWidth() const;     // the width rounded up to even
  int codedHeight() const;    // the height rounded up to even
  const std::string& path() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

struct VideoInfo {
  int frames = 0;  // frames decoded (every one is decoded: not the container's claim)
  int width = 0;   // the coded size
  int height = 0;
  std::string codec;  // "h264", "h265", "vp9", or FFmpeg's name of another codec
  double fps = 0;     // the stream's frame rate
};

// One decoded frame as 8-bit sRGB codes (width x height RGB triples, row 0 at the top).
struct VideoFrame {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;
};

// Decodes every frame of the first video stream of `path` (any container and codec FFmpeg
// reads), calling onFrame(index, frame) for each when given. Throws InputError naming the
// file when it is missing, not a video or damaged. The conversion to RGB is FFmpeg's most
// accurate (bicubic chroma, exact rounding); `playback` trades that for speed (bilinear chroma:
// a quilt video played as it is decoded, where the accurate conversion took 60 % of the time).
VideoInfo probeVideo(const std::string& path,
                     const std::function<void(int, const VideoFrame&)>& onFrame = {},
                     bool playback = false);
// Frame `index` (from 0) in linear light; throws InputError when there is no such frame.
Image decodeVideoFrame(const std::string& path, int index);

}  // namespace parallax
