#include "parallax/jobs/quilt_player.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/image_file.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/requests.h"
#include "parallax/render/quilt.h"
#include "parallax/video/video_writer.h"

namespace parallax::jobs {

namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

// Frames decoded ahead of the screen.
constexpr size_t kFramesAhead = 3;

// Thrown inside FFmpeg's frame callback to stop decoding when the player closes.
struct Stopped {};

}  // namespace

bool isVideoPath(const std::string& path) {
  std::string ext = path.substr(std::min(path.size(), path.rfind('.')));
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".mp4" || ext == ".webm" || ext == ".mkv" || ext == ".mov" || ext == ".avi";
}

struct QuiltPlayer::State {
  QuiltPlayRequest request;
  std::unique_ptr<QuiltInterlacer> interlacer;
  int quiltWidth = 0, quiltHeight = 0;
  VideoInfo video;               // frames 0: a picture
  std::vector<uint8_t> picture;  // a picture's panel frame

  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::vector<uint8_t>> ready;  // frames made, oldest first
  // Frames shown, handed back to be made again: no allocation (and no page faults) per frame.
  std::vector<std::vector<uint8_t>> spare;
  bool stop = false;
  std::exception_ptr error;
  Timing timing;
  std::thread decoder;

  // The decoding thread: the video from its start, again and again, each frame interlaced and
  // queued (waiting while kFramesAhead are).
  void decode() {
    try {
      while (true) {
        auto last = Clock::now();
        probeVideo(
            request.quilt,
            [&](int, const VideoFrame& frame) {
              const auto decoded = Clock::now();
              if (frame.width != quiltWidth || frame.height != quiltHeight)
                throw InputError(request.quilt, "", "its frames change size");
              std::vector<uint8_t> panel;
              {
                std::lock_guard<std::mutex> lock(mutex);
                if (!spare.empty()) panel = std::move(spare.back()), spare.pop_back();
              }
              panel.resize(size_t(interlacer->panelWidth()) * size_t(interlacer->panelHeight()) *
                           3);
              interlacer->interlace(frame.rgb.data(), panel.data());
              const auto interlaced = Clock::now();
              std::unique_lock<std::mutex> lock(mutex);
              timing.decodeSeconds += seconds(decoded - last);
              timing.interlaceSeconds += seconds(interlaced - decoded);
              ++timing.frames;
              changed.wait(lock, [&] { return stop || ready.size() < kFramesAhead; });
              if (stop) throw Stopped{};
              ready.push_back(std::move(panel));
              changed.notify_all();
              lock.unlock();
              last = Clock::now();
            },
            true);
        std::lock_guard<std::mutex> lock(mutex);
        if (stop) return;
      }
    } catch (const Stopped&) {
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      error = std::current_exception();
      changed.notify_all();
    }
  }
};

QuiltPlayer::QuiltPlayer(const QuiltPlayRequest& r, Reporter& reporter)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.request = r;
  const DisplayDescription description = r.display.describe(reporter);
  if (description.kind != DisplayKind::Lenticular)
    throw RequestError("display",
                       "a quilt is played on a lenticular panel (a calibration or lkg:NAME); "
                       "for a barrier display, map it with `parallax interlace` and show that");
  const BuiltDisplay display = makeDisplay(description, r.display.camera());
  const LenticularDesign& design = *display->lenticularDesign();
  ViewResampling resampling = ViewResampling::Linear;
  if (r.viewResampling == "nearest")
    resampling = ViewResampling::Nearest;
  else if (r.viewResampling != "linear")
    throw RequestError("view_resampling",
                       "expected nearest or linear, got '" + r.viewResampling + "'");
  const QuiltLayout layout = parseQuiltName(r.quilt);
  const bool video = isVideoPath(r.quilt);
  if (video) {
    s.video = probeVideo(r.quilt);
    if (s.video.frames < 1) throw InputError(r.quilt, "", "has no frames");
    s.quiltWidth = s.video.width;
    s.quiltHeight = s.video.height;
  } else {
    const ImageInfo info = readImageInfo(r.quilt);
    s.quiltWidth = info.width;
    s.quiltHeight = info.height;
  }
  if (s.quiltWidth < layout.columns || s.quiltHeight < layout.rows)
    throw InputError(r.quilt, "",
                     std::to_string(s.quiltWidth) + "x" + std::to_string(s.quiltHeight) +
                         " pixels are too few for its " + std::to_string(layout.columns) + "x" +
                         std::to_string(layout.rows) + " tiles");
  // The table, a quilt frame (FFmpeg's and ours), the frames ahead and the one shown.
  const double panelPixels = double(design.calibration.screenW) * design.calibration.screenH;
  const double quiltPixels = double(s.quiltWidth) * s.quiltHeight;
  checkPeakMemory(r.otherBytes +
                      panelPixels * (QuiltInterlacer::bytesPerPanelPixel() +
                                     3.0 * (kFramesAhead + 2) + r.otherBytesPerPanelPixel) +
                      quiltPixels * (video ? 3.0 * 3 : kFloatRgbPixelBytes + 4),
                  r.quilt, "the quilt's player", "play a smaller quilt");
  s.interlacer =
      std::make_unique<QuiltInterlacer>(design, layout, s.quiltWidth, s.quiltHeight, resampling);
  if (video) {
    s.decoder = std::thread([&s] { s.decode(); });
  } else {
    const Image quilt = readImage(r.quilt);
    std::vector<uint8_t> codes(size_t(quiltPixels) * 3);
    linearToSrgb8(&quilt.pixels()[0].x, codes.size(), codes.data());
    s.picture.resize(size_t(panelPixels) * 3);
    const auto start = Clock::now();
    s.interlacer->interlace(codes.data(), s.picture.data());
    s.timing.interlaceSeconds = seconds(Clock::now() - start);
    s.timing.frames = 1;
  }
}

QuiltPlayer::~QuiltPlayer() {
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    state_->stop = true;
  }
  state_->changed.notify_all();
  if (state_->decoder.joinable()) state_->decoder.join();
}

int QuiltPlayer::width() const {
  return state_->interlacer->panelWidth();
}
int QuiltPlayer::height() const {
  return state_->interlacer->panelHeight();
}
bool QuiltPlayer::isVideo() const {
  return state_->video.frames > 0;
}
double QuiltPlayer::fps() const {
  return state_->video.fps;
}
int QuiltPlayer::frames() const {
  return isVideo() ? state_->video.frames : 1;
}

bool QuiltPlayer::next(std::vector<uint8_t>& rgb) {
  State& s = *state_;
  if (!isVideo()) {
    rgb = s.picture;
    return true;
  }
  std::unique_lock<std::mutex> lock(s.mutex);
  s.changed.wait(lock, [&] { return !s.ready.empty() || s.error; });
  if (s.ready.empty()) std::rethrow_exception(s.error);
  std::swap(rgb, s.ready.front());
  if (rgb.size() == s.ready.front().size() || s.ready.front().empty())
    s.spare.push_back(std::move(s.ready.front()));
  s.ready.pop_front();
  s.changed.notify_all();
  return true;
}

QuiltPlayer::Timing QuiltPlayer::timing() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->timing;
}

}  // namespace parallax::jobs
