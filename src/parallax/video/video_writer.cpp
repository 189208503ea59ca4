// Encoding and decoding through FFmpeg's libraries (libavformat for the containers, libavcodec
// for the codecs, libswscale for RGB <-> YUV). The steps follow FFmpeg's own examples of the
// send/receive API (doc/examples/encode_video.c, mux.c, demux_decode.c); see docs/video.md.
#include "parallax/video/video_writer.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/cpu.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <system_error>

#include "parallax/core/error.h"
#include "parallax/core/output_path.h"

// LeakSanitizer (PARALLAX_SANITIZE): Debian's libx265 (3.5) leaks about 1.2 kB per encoder it
// opens (x265_malloc inside x265_encoder_open, and the strdup'd "pools" value), freed by
// nothing FFmpeg or we can call. Those are suppressed, by the library's name only, in every
// program that links this module; a leak anywhere else is still reported. Debian's libx264
// (0.164) leaks its parsed parameters (about 330 bytes) when it refuses to open an encoder, as
// checkVideoSize's probe of a frame too large for H.264 makes it do.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libx265.so\nleak:libx264.so\n";
}
// ...and silently: LeakSanitizer's table of the suppressions it used goes to stderr, which
// would turn a refusal's one line into five.
extern "C" const char* __lsan_default_options() {
  return "print_suppressions=0";
}

namespace parallax {

namespace {

namespace fs = std::filesystem;

// Encoder threads, fixed: x264's and x265's output depends on how many frames they encode at
// once (a frame thread may only reference the rows its predecessor has finished), so a count
// taken from the machine would make the bytes depend on the machine. Four keeps two to four
// cores busy; more would change nothing on the machines this runs on and the file would differ.
constexpr int kEncoderThreads = 4;

// FFmpeg logs through av_log to stderr by default; library code never prints, so the messages
// are kept (the last error of this thread) and put into the RequestError instead.
thread_local std::string lastLogMessage;

void logCallback(void* /*avcl*/, int level, const char* format, va_list args) {
  if (level > AV_LOG_ERROR) return;
  char line[512];
  std::vsnprintf(line, sizeof line, format, args);
  std::string text(line);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  if (!text.empty()) lastLogMessage = text;
}

void quietLogs() {
  static std::once_flag once;
  std::call_once(once, [] {
    av_log_set_level(AV_LOG_ERROR);
    av_log_set_callback(logCallback);
  });
}

std::string avError(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  std::string message(text);
  if (!lastLogMessage.empty()) message += " (" + lastLogMessage + ")";
  return message;
}

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// The containers by extension, and the codecs each carries here. MP4 carries VP9 too, but
// players' support of that pairing is patchy, so VP9 goes to WebM (or Matroska).
struct Container {
  const char* extension;
  const char* muxer;  // FFmpeg's name
  std::vector<std::string> codecs;
};

const std::vector<Container>& containers() {
  static const std::vector<Container> list{{".mp4", "mp4", {"h264", "h265"}},
                                           {".webm", "webm", {"vp9"}},
                                           {".mkv", "matroska", {"h264", "h265", "vp9"}}};
  return list;
}

const Container& containerOf(const std::string& path, const VideoFieldNames& names) {
  const std::string ext = lowerExtension(path);
  for (const Container& c : containers())
    if (ext == c.extension) return c;
  throw RequestError(names.file,
                     "unknown video extension '" + ext + "': expected .mp4, .webm or .mkv", path);
}

const char* encoderName(const std::string& codec) {
  if (codec == "h264") return "libx264";
  if (codec == "h265") return "libx265";
  return "libvpx-vp9";
}

int maxQuality(const std::string& codec) {
  return codec == "vp9" ? 63 : 51;
}

// An FFmpeg object freed by its own function when the holder goes.
template <typename T, void (*Free)(T**)>
struct Owned {
  T* p = nullptr;
  Owned() = default;
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() {
    if (p) Free(&p);
  }
  T* operator->() const { return p; }
};

void freeFrame(AVFrame** f) {
  av_frame_free(f);
}
void freePacket(AVPacket** p) {
  av_packet_free(p);
}
void freeCodec(AVCodecContext** c) {
  avcodec_free_context(c);
}
void closeInput(AVFormatContext** f) {
  avformat_close_input(f);
}
void freeDictionary(AVDictionary** d) {
  av_dict_free(d);
}

struct SwsHolder {
  SwsContext* p = nullptr;
  SwsHolder() = default;
  SwsHolder(const SwsHolder&) = delete;
  SwsHolder& operator=(const SwsHolder&) = delete;
  ~SwsHolder() { sws_freeContext(p); }
};

// libvpx's VP9 encoder opens at any size up to 65536 but fails its first frame ("Failed to
// allocate last frame buffer") beyond 16384 a side (measured with Debian's libvpx): refused
// with the others' limits, before any frame.
void refuseBeyondVp9(const std::string& codec, int width, int height, const VideoFieldNames& names,
                     const std::string& path) {
  if (codec == "vp9" && (width > 16384 || height > 16384))
    throw RequestError(names.file,
                       "the libvpx-vp9 encoder takes at most 16384 pixels a side, not " +
                           std::to_string(width) + "x" + std::to_string(height) +
                           ": use a smaller size, or h265 (.mp4, .mkv)",
                       path);
}

// Sets up `e` for `codecName` at the coded size and opens it: the one setup of open() and
// checkVideoSize(). Returns avcodec_open2's code.
int openEncoder(AVCodecContext* e, const AVCodec* codec, const std::string& codecName,
                int codedWidth, int codedHeight, const VideoOptions& options) {
  e->width = codedWidth;
  e->height = codedHeight;
  e->pix_fmt = AV_PIX_FMT_YUV420P;
  e->framerate = av_d2q(options.fps, 100000);
  e->time_base = av_inv_q(e->framerate);
  e->sample_aspect_ratio = AVRational{1, 1};
  // What the codes mean, so that players convert back as they were made: BT.709 primaries
  // (sRGB's), the sRGB transfer (IEC 61966-2-1), BT.709's YUV matrix in limited range.
  e->color_primaries = AVCOL_PRI_BT709;
  e->color_trc = AVCOL_TRC_IEC61966_2_1;
  e->colorspace = AVCOL_SPC_BT709;
  e->color_range = AVCOL_RANGE_MPEG;
  e->thread_count = kEncoderThreads;
  e->flags |= AV_CODEC_FLAG_BITEXACT;

  Owned<AVDictionary, freeDictionary> opts;
  const std::string crf = std::to_string(options.quality);
  av_dict_set(&opts.p, "crf", crf.c_str(), 0);
  if (codecName == "h264") {
    av_dict_set(&opts.p, "preset", "medium", 0);
    // x264's AVX-512 kernels (Debian's 0.164) make different bytes from the same frames from
    // one encode to the next (measured: 1613, 1617, 1620 or 1621 bytes for the same six
    // frames, in one process); limited to its AVX2 kernels, as on every CPU without AVX-512,
    // the bytes are the same every time. x264 takes the named set as given, so it is asked
    // for only where the CPU has it (AVX-512 implies AVX2, FMA3 and BMI2 there).
    if (av_get_cpu_flags() & AV_CPU_FLAG_AVX512) av_dict_set(&opts.p, "x264-params", "asm=AVX2", 0);
  } else if (codecName == "h265") {
    av_dict_set(&opts.p, "preset", "medium", 0);
    // A fixed pool and frame-thread count (see kEncoderThreads): x265's bytes depend on both
    // (measured: pools 1, 2, 3, 4 and the machine's default give five different files).
    // x265's own log off.
    av_dict_set(&opts.p, "x265-params", "pools=4:frame-threads=2:log-level=error", 0);
  } else {
    // libvpx's constant-quality mode needs a zero bitrate beside the crf; "good" at cpu-used 4
    // is its usual speed for files (0 is several times slower for about 1 dB); row-mt keeps
    // the threads busy on one tile column of small pictures.
    e->bit_rate = 0;
    av_dict_set(&opts.p, "deadline", "good", 0);
    av_dict_set(&opts.p, "cpu-used", "4", 0);
    av_dict_set(&opts.p, "row-mt", "1", 0);
  }
  lastLogMessage.clear();
  return avcodec_open2(e, codec, &opts.p);
}

}  // namespace

std::string resolveVideoCodec(const std::string& path, const VideoOptions& options, int width,
                              int height, const VideoFieldNames& names) {
  const Container& container = containerOf(path, names);
  std::string codec = options.codec;
  if (codec == "auto") {
    if (container.muxer == std::string("webm"))
      codec = "vp9";
    else
      codec = (width > 4096 || height > 4096) ? "h265" : "h264";
  }
  if (codec != "h264" && codec != "h265" && codec != "vp9")
    throw RequestError(names.codec,
                       "unknown codec '" + options.codec + "': expected auto, h264, h265 or vp9");
  if (std::find(container.codecs.begin(), container.codecs.end(), codec) ==
      container.codecs.end()) {
    std::string allowed;
    for (const std::string& c : container.codecs) allowed += (allowed.empty() ? "" : ", ") + c;
    throw RequestError(names.codec, "a " + std::string(container.extension) + " file carries " +
                                        allowed + ", not " + codec +
                                        (codec == "vp9" ? " (use .webm or .mkv)" : ""));
  }
  return codec;
}

void checkVideoOptions(const std::string& path, const VideoOptions& options,
                       const VideoFieldNames& names) {
  quietLogs();
  if (path.empty()) throw RequestError(names.file, "no file name given");
  // Size-dependent only for "auto" in MP4 (h264 or h265); both are checked below then.
  const std::string codec = resolveVideoCodec(path, options, 0, 0, names);
  std::vector<std::string> needed{codec};
  if (options.codec == "auto" && codec == "h264") needed.push_back("h265");
  for (const std::string& c : needed)
    if (!avcodec_find_encoder_by_name(encoderName(c)))
      throw RequestError(names.codec,
                         "this FFmpeg has no " + std::string(encoderName(c)) + " encoder for " + c);
  if (options.quality < 0 || options.quality > maxQuality(codec))
    throw RequestError(names.quality, "expected 0 to " + std::to_string(maxQuality(codec)) +
                                          " for " + codec + " (lower is better), got " +
                                          std::to_string(options.quality));
  if (!(options.fps > 0 && options.fps <= 240))
    throw RequestError(names.fps, "expected a frame rate above 0 and at most 240, got " +
                                      std::to_string(options.fps));
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw RequestError(names.file, "is a folder, not a video file name", path);
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && fs::exists(parent, ec) && !fs::is_directory(parent, ec))
    throw RequestError(names.file, "its folder '" + parent.string() + "' is a file", path);
  // A file that cannot be written, or a folder that cannot take it: refused now, not after the
  // frames are rendered.
  try {
    checkOutputFile(path);
  } catch (const InputError& e) {
    throw RequestError(names.file, e.what(), path);
  }
}

namespace {

// What open() and checkVideoSize() refuse before an encoder is opened: the options, a size
// beyond 1 to 65536 a side, VP9's 16384. Returns the codec for that size.
std::string checkedCodec(const std::string& path, int width, int height,
                         const VideoOptions& options, const VideoFieldNames& names) {
  checkVideoOptions(path, options, names);
  if (width < 1 || height < 1 || width > 65536 || height > 65536)
    throw RequestError(names.file,
                       "a video frame of " + std::to_string(width) + "x" + std::to_string(height) +
                           " pixels: expected 1 to 65536 a side",
                       path);
  const std::string codec = resolveVideoCodec(path, options, width, height, names);
  refuseBeyondVp9(codec, width, height, names, path);
  return codec;
}

}  // namespace

void checkVideoSize(const std::string& path, int width, int height, const VideoOptions& options,
                    const VideoFieldNames& names) {
  const std::string codecName = checkedCodec(path, width, height, options, names);
  // libvpx allocates its frame buffers when it opens (measured at 8192 x 8192: 6.9 s and
  // 3.6 GB), and its only size limit is checked by name above: not opened twice.
  if (codecName == "vp9") return;
  const AVCodec* codec = avcodec_find_encoder_by_name(encoderName(codecName));
  if (!codec)
    throw RequestError(names.codec, "this FFmpeg has no " + std::string(encoderName(codecName)) +
                                        " encoder for " + codecName);
  // The encoder itself is the truth about its limits (x264's 16384 a side, x265's minimum
  // sizes, the even sizes of 4:2:0, which the coded size pads to): it is opened at the coded
  // size and closed again, without a file (measured: 8 ms at 1920 x 1080 and 32 ms at
  // 4096 x 4096 for x264, 13 ms at 8192 x 8192 for x265).
  Owned<AVCodecContext, freeCodec> encoder;
  encoder.p = avcodec_alloc_context3(codec);
  if (!encoder.p) throw std::bad_alloc();
  const int codedWidth = width + (width & 1), codedHeight = height + (height & 1);
  const int r = openEncoder(encoder.p, codec, codecName, codedWidth, codedHeight, options);
  if (r < 0)
    throw RequestError(
        names.file,
        "the " + std::string(encoderName(codecName)) + " encoder refuses " + std::to_string(width) +
            "x" + std::to_string(height) + " frames (coded " + std::to_string(codedWidth) + "x" +
            std::to_string(codedHeight) + "): " + avError(r) + "; nothing was rendered",
        path);
}

struct VideoWriter::State {
  std::string path, tmpPath, codec;
  VideoFieldNames names;
  int width = 0, height = 0, codedWidth = 0, codedHeight = 0;
  AVFormatContext* format = nullptr;
  Owned<AVCodecContext, freeCodec> encoder;
  AVStream* stream = nullptr;
  SwsHolder sws;
  Owned<AVFrame, freeFrame> frame;
  Owned<AVPacket, freePacket> packet;
  std::vector<uint8_t> padded;  // the coded size's RGB codes
  int64_t frames = 0;
  bool finished = false;

  ~State() {
    if (format) {
      if (format->pb) avio_closep(&format->pb);
      avformat_free_context(format);
    }
    if (!finished && !tmpPath.empty()) {
      std::error_code ec;
      fs::remove(tmpPath, ec);
    }
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw RequestError(names.file, message, path);
  }

  // Sends one frame (nullptr: the end) and writes every packet the encoder has ready.
  void encode(const AVFrame* f) {
    lastLogMessage.clear();
    int r = avcodec_send_frame(encoder.p, f);
    if (r < 0) fail("encoding failed: " + avError(r));
    for (;;) {
      r = avcodec_receive_packet(encoder.p, packet.p);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      if (r < 0) fail("encoding failed: " + avError(r));
      av_packet_rescale_ts(packet.p, encoder->time_base, stream->time_base);
      packet->stream_index = stream->index;
      r = av_interleaved_write_frame(format, packet.p);
      if (r < 0) fail("writing failed: " + avError(r));
    }
  }
};

VideoWriter::VideoWriter() = default;
VideoWriter::~VideoWriter() = default;

bool VideoWriter::isOpen() const {
  return state_ && !state_->finished;
}
int VideoWriter::frames() const {
  return state_ ? int(state_->frames) : 0;
}
std::string VideoWriter::codec() const {
  return state_ ? state_->codec : std::string();
}
int VideoWriter::codedWidth() const {
  return state_ ? state_->codedWidth : 0;
}
int VideoWriter::codedHeight() const {
  return state_ ? state_->codedHeight : 0;
}
const std::string& VideoWriter::path() const {
  static const std::string none;
  return state_ ? state_->path : none;
}

void VideoWriter::open(const std::string& path, int width, int height, const VideoOptions& options,
                       const VideoFieldNames& names) {
  const std::string codecName = checkedCodec(path, width, height, options, names);
  state_.reset();  // a writer opened again drops (and removes) what it had
  auto s = std::make_unique<State>();
  s->path = path;
  s->names = names;
  s->codec = codecName;
  s->width = width;
  s->height = height;
  // YUV 4:2:0 codes one chroma sample per 2 x 2 pixels: the coded size is even.
  s->codedWidth = width + (width & 1);
  s->codedHeight = height + (height & 1);
  const Container& container = containerOf(path, names);

  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (ec) s->fail("cannot create its folder: " + ec.message());
  removeStaleTemporaryFiles(path);  // a killed run's FILE.partial-PID
  s->tmpPath = path + ".partial-" + std::to_string(::getpid());

  lastLogMessage.clear();
  int r = avformat_alloc_output_context2(&s->format, nullptr, container.muxer, s->tmpPath.c_str());
  if (r < 0 || !s->format) s->fail("cannot start a " + std::string(container.muxer) + " file");
  // No library versions or times in the file: the same frames give the same bytes.
  s->format->flags |= AVFMT_FLAG_BITEXACT;

  const AVCodec* codec = avcodec_find_encoder_by_name(encoderName(s->codec));
  if (!codec) s->fail("this FFmpeg has no " + std::string(encoderName(s->codec)) + " encoder");
  s->stream = avformat_new_stream(s->format, nullptr);
  s->encoder.p = avcodec_alloc_context3(codec);
  s->frame.p = av_frame_alloc();
  s->packet.p = av_packet_alloc();
  if (!s->stream || !s->encoder.p || !s->frame.p || !s->packet.p) s->fail("out of memory");

  AVCodecContext* e = s->encoder.p;
  if (s->format->oformat->flags & AVFMT_GLOBALHEADER) e->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  r = openEncoder(e, codec, s->codec, s->codedWidth, s->codedHeight, options);
  if (r < 0)
    s->fail("the " + std::string(encoderName(s->codec)) + " encoder refuses " +
            std::to_string(s->codedWidth) + "x" + std::to_string(s->codedHeight) + " at " +
            std::to_string(options.fps) + " fps: " + avError(r));
  r = avcodec_parameters_from_context(s->stream->codecpar, e);
  if (r < 0) s->fail(avError(r));
  s->stream->time_base = e->time_base;
  s->stream->avg_frame_rate = e->framerate;
  // Apple's players play HEVC in MP4 only under the 'hvc1' sample entry (parameter sets in the
  // header), not FFmpeg's default 'hev1'.
  if (s->codec == "h265" && container.muxer == std::string("mp4"))
    s->stream->codecpar->codec_tag = MKTAG('h', 'v', 'c', '1');

  lastLogMessage.clear();
  r = avio_open(&s->format->pb, s->tmpPath.c_str(), AVIO_FLAG_WRITE);
  if (r < 0) s->fail("cannot write '" + s->tmpPath + "': " + avError(r));
  Owned<AVDictionary, freeDictionary> muxOpts;
  // The index first, so that a browser starts playing before the whole file is there.
  if (container.muxer == std::string("mp4")) av_dict_set(&muxOpts.p, "movflags", "+faststart", 0);
  r = avformat_write_header(s->format, &muxOpts.p);
  if (r < 0) s->fail("cannot write the header: " + avError(r));

  s->frame->format = AV_PIX_FMT_YUV420P;
  s->frame->width = s->codedWidth;
  s->frame->height = s->codedHeight;
  s->frame->color_primaries = e->color_primaries;
  s->frame->color_trc = e->color_trc;
  s->frame->colorspace = e->colorspace;
  s->frame->color_range = e->color_range;
  r = av_frame_get_buffer(s->frame.p, 0);
  if (r < 0) s->fail("out of memory: " + avError(r));
  // BITEXACT: the same codes on every CPU (no SIMD shortcuts that round differently);
  // ACCURATE_RND: rounded, not truncated, arithmetic.
  s->sws.p = sws_getContext(
      s->codedWidth, s->codedHeight, AV_PIX_FMT_RGB24, s->codedWidth, s->codedHeight,
      AV_PIX_FMT_YUV420P, SWS_BICUBIC | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr, nullptr, nullptr);
  if (!s->sws.p) s->fail("no RGB to YUV 4:2:0 conversion");
  const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
  // Source: full-range RGB; destination: BT.709 limited range (16-235 luma, 16-240 chroma).
  sws_setColorspaceDetails(s->sws.p, bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16);
  // swscale's SIMD reads up to 16 bytes past the last row's end (valgrind: "Invalid read of
  // size 16" 12 bytes beyond the block): 64 bytes of zeros after the picture keep that inside.
  s->padded.resize(size_t(s->codedWidth) * size_t(s->codedHeight) * 3 + 64);
  state_ = std::move(s);
}

void VideoWriter::addFrame8(const uint8_t* rgb, int width, int height) {
  if (!isOpen()) throw std::logic_error("VideoWriter::addFrame before open");
  State& s = *state_;
  if (width != s.width || height != s.height)
    s.fail("frame " + std::to_string(s.frames) + " is " + std::to_string(width) + "x" +
           std::to_string(height) + ", the video " + std::to_string(s.width) + "x" +
           std::to_string(s.height));
  // Copy into the coded size; an odd side repeats its last column (row).
  const size_t inRow = size_t(width) * 3, outRow = size_t(s.codedWidth) * 3;
  for (int y = 0; y < s.codedHeight; ++y) {
    const uint8_t* src = rgb + size_t(std::min(y, height - 1)) * inRow;
    uint8_t* dst = s.padded.data() + size_t(y) * outRow;
    std::memcpy(dst, src, inRow);
    if (s.codedWidth > width) std::memcpy(dst + inRow, src + inRow - 3, 3);
  }
  int r = av_frame_make_writable(s.frame.p);
  if (r < 0) s.fail("out of memory: " + avError(r));
  const uint8_t* planes[1] = {s.padded.data()};
  const int strides[1] = {int(outRow)};
  sws_scale(s.sws.p, planes, strides, 0, s.codedHeight, s.frame->data, s.frame->linesize);
  s.frame->pts = s.frames;
  s.encode(s.frame.p);
  ++s.frames;
}

void VideoWriter::addFrame(const Image& image) {
  if (!isOpen()) throw std::logic_error("VideoWriter::addFrame before open");
  std::vector<uint8_t> codes(image.pixels().size() * 3);
  if (!codes.empty())
    linearToSrgb8(&image.pixels().front().x, image.pixels().size() * 3, codes.data());
  addFrame8(codes.data(), image.width(), image.height());
}

void VideoWriter::finish() {
  if (!isOpen()) throw std::logic_error("VideoWriter::finish before open");
  State& s = *state_;
  if (s.frames == 0) {
    const std::string path = s.path;
    const VideoFieldNames names = s.names;
    state_.reset();  // removes the temporary file
    throw RequestError(names.file, "no frames to write", path);
  }
  s.encode(nullptr);
  lastLogMessage.clear();
  int r = av_write_trailer(s.format);
  if (r < 0) s.fail("cannot finish the file: " + avError(r));
  r = avio_closep(&s.format->pb);
  if (r < 0) s.fail("cannot close the file: " + avError(r));
  std::error_code ec;
  fs::rename(s.tmpPath, s.path, ec);
  if (ec) s.fail("cannot move the video into place: " + ec.message());
  s.finished = true;
}

VideoInfo probeVideo(const std::string& path,
                     const std::function<void(int, const VideoFrame&)>& onFrame, bool playback) {
  quietLogs();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(path, "", fs::exists(path, ec) ? "not a file" : "no such file");
  lastLogMessage.clear();
  Owned<AVFormatContext, closeInput> input;
  int r = avformat_open_input(&input.p, path.c_str(), nullptr, nullptr);
  if (r < 0) throw InputError(path, "", "not a video FFmpeg reads: " + avError(r));
  r = avformat_find_stream_info(input.p, nullptr);
  if (r < 0) throw InputError(path, "", "no stream information: " + avError(r));
  const AVCodec* codec = nullptr;
  const int index = av_find_best_stream(input.p, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (index < 0 || !codec) throw InputError(path, "", "no video stream FFmpeg decodes");
  AVStream* stream = input->streams[index];
  Owned<AVCodecContext, freeCodec> decoder;
  decoder.p = avcodec_alloc_context3(codec);
  Owned<AVFrame, freeFrame> frame;
  frame.p = av_frame_alloc();
  Owned<AVPacket, freePacket> packet;
  packet.p = av_packet_alloc();
  if (!decoder.p || !frame.p || !packet.p) throw std::bad_alloc();
  r = avcodec_parameters_to_context(decoder.p, stream->codecpar);
  if (r < 0) throw InputError(path, "", avError(r));
  // Every core (FFmpeg's choice of frame or slice threads; the pictures are the same whatever
  // the count): a 3360x3360 quilt video is decoded as it plays (parallax show).
  decoder->thread_count = 0;
  r = avcodec_open2(decoder.p, codec, nullptr);
  if (r < 0) throw InputError(path, "", "cannot open its decoder: " + avError(r));

  VideoInfo info;
  const std::string name = avcodec_get_name(stream->codecpar->codec_id);
  info.codec = name == "hevc" ? "h265" : name;
  info.fps = av_q2d(av_guess_frame_rate(input.p, stream, nullptr));
  SwsHolder sws;
  VideoFrame rgb;
  const auto receive = [&] {
    for (;;) {
      r = avcodec_receive_frame(decoder.p, frame.p);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      if (r < 0) throw InputError(path, "", "damaged video: " + avError(r));
      if (info.frames == 0) {
        info.width = frame->width;
        info.height = frame->height;
      }
      if (onFrame) {
        sws.p = sws_getCachedContext(
            sws.p, frame->width, frame->height, AVPixelFormat(frame->format), frame->width,
            frame->height, AV_PIX_FMT_RGB24,
            playback ? SWS_BILINEAR
                     : SWS_BICUBIC | SWS_ACCURATE_RND | SWS_BITEXACT | SWS_FULL_CHR_H_INT,
            nullptr, nullptr, nullptr);
        if (!sws.p) throw InputError(path, "", "no conversion of its pixels to RGB");
        // The stream's matrix (BT.709 unless it says BT.601) and range.
        const int matrix =
            frame->colorspace == AVCOL_SPC_BT470BG || frame->colorspace == AVCOL_SPC_SMPTE170M
                ? SWS_CS_ITU601
                : SWS_CS_ITU709;
        const int* table = sws_getCoefficients(matrix);
        sws_setColorspaceDetails(sws.p, table, frame->color_range == AVCOL_RANGE_JPEG ? 1 : 0,
                                 table, 1, 0, 1 << 16, 1 << 16);
        rgb.width = frame->width;
        rgb.height = frame->height;
        rgb.rgb.resize(size_t(frame->width) * size_t(frame->height) * 3);
        uint8_t* planes[1] = {rgb.rgb.data()};
        const int strides[1] = {frame->width * 3};
        sws_scale(sws.p, frame->data, frame->linesize, 0, frame->height, planes, strides);
        onFrame(info.frames, rgb);
      }
      ++info.frames;
      av_frame_unref(frame.p);
    }
  };
  while ((r = av_read_frame(input.p, packet.p)) >= 0) {
    if (packet->stream_index == index) {
      lastLogMessage.clear();
      const int sent = avcodec_send_packet(decoder.p, packet.p);
      av_packet_unref(packet.p);
      if (sent < 0) throw InputError(path, "", "damaged video: " + avError(sent));
      receive();
    } else {
      av_packet_unref(packet.p);
    }
  }
  if (r != AVERROR_EOF) throw InputError(path, "", "damaged video: " + avError(r));
  avcodec_send_packet(decoder.p, nullptr);  // drain the frames the decoder holds
  receive();
  if (info.frames == 0) throw InputError(path, "", "the video has no frames");
  return info;
}

Image decodeVideoFrame(const std::string& path, int index) {
  Image image;
  const VideoInfo info = probeVideo(path, [&](int k, const VideoFrame& f) {
    if (k != index) return;
    image = Image(f.width, f.height);
    for (size_t i = 0; i < image.pixels().size(); ++i)
      image.pixels()[i] = Vec3f(srgb8ToLinear(f.rgb[3 * i]), srgb8ToLinear(f.rgb[3 * i + 1]),
                                srgb8ToLinear(f.rgb[3 * i + 2]));
  });
  if (index < 0 || index >= info.frames)
    throw InputError(
        path, "",
        "has " + std::to_string(info.frames) + " frames, no frame " + std::to_string(index));
  return image;
}

}  // namespace parallax
