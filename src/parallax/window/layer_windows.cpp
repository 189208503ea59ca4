#include "parallax/window/layer_windows.h"

#include <SDL2/SDL.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

#include "parallax/core/error.h"

namespace parallax {

namespace {

std::runtime_error sdlError(const std::string& what) {
  return std::runtime_error(what + ": " + SDL_GetError());
}

ShowKey keyOf(SDL_Keycode key) {
  switch (key) {
    case SDLK_RIGHT:
    case SDLK_SPACE:
    case SDLK_n:
      return ShowKey::Next;
    case SDLK_LEFT:
    case SDLK_BACKSPACE:
    case SDLK_p:
      return ShowKey::Previous;
    case SDLK_i:
      return ShowKey::Info;
    case SDLK_q:
    case SDLK_ESCAPE:
      return ShowKey::Quit;
    default:
      return ShowKey::Other;
  }
}

// Starts SDL's video on a real display: X11, Wayland (when its socket is there) or the console's
// KMS/DRM, never SDL's offscreen fallback, which would "show" the layers nowhere. A driver the
// user names in SDL_VIDEODRIVER is taken as given.
// Once per process, and quit only when the process ends: an X server that has no other client
// resets when the last connection closes, and refuses new ones while it does, so counting the
// monitors, quitting and starting again for the windows failed about 40 % of the time there.
// For the same reason a refused first connection is tried again for a few seconds when DISPLAY
// names a server: one whose last client (a screenshot, the show before) has just left is
// resetting for some milliseconds, and one started with the show is not listening yet.
bool initVideo() {
  static bool started = false;
  if (started) return true;
  if (!std::getenv("SDL_VIDEODRIVER")) {
    const bool wayland = std::getenv("WAYLAND_DISPLAY") && std::getenv("XDG_RUNTIME_DIR");
    SDL_SetHint(SDL_HINT_VIDEODRIVER, wayland ? "wayland,x11,kmsdrm" : "x11,kmsdrm");
  }
  const char* display = std::getenv("DISPLAY");
  const bool xServerNamed = display && *display;
  constexpr int kAttempts = 30;  // 3 s in all, at 100 ms apart
  for (int attempt = 1; SDL_Init(SDL_INIT_VIDEO) != 0; ++attempt) {
    if (!xServerNamed || attempt == kAttempts) return false;
    SDL_Delay(100);
  }
  started = true;
  std::atexit(SDL_Quit);
  return true;
}

}  // namespace

struct LayerWindows::Impl {
  struct Window {
    SDL_Window* window = nullptr;
    SDL_Renderer* renderer = nullptr;
    std::vector<SDL_Texture*> frames;  // one per frame (one for a still picture)
    SDL_Texture* texture = nullptr;    // the frame shown
    int width = 0, height = 0;
    FrameSource stream;  // frames made as they are shown (texture: a streaming one)
    std::vector<uint8_t> streamed;
  };
  std::vector<Window> windows;

  ~Impl() {
    for (Window& w : windows) {
      clearFrames(w);
      if (w.renderer) SDL_DestroyRenderer(w.renderer);
      if (w.window) SDL_DestroyWindow(w.window);
    }
  }

  // Window `index` shows `frames` (all one size) in turn, the first now.
  void setFrames(int index, const std::vector<const Image*>& frames);

  static void clearFrames(Window& w) {
    for (SDL_Texture* t : w.frames) SDL_DestroyTexture(t);
    w.frames.clear();
    w.texture = nullptr;
    w.stream = nullptr;
  }

  // The stream's next frame into its texture; false after its last.
  static bool nextStreamed(Window& w) {
    if (!w.stream(w.streamed)) return false;
    if (w.streamed.size() != size_t(w.width) * size_t(w.height) * 3)
      throw std::invalid_argument("LayerWindows::streamFrames: a frame of another size");
    SDL_UpdateTexture(w.texture, nullptr, w.streamed.data(), w.width * 3);
    return true;
  }

  void present(Window& w) {
    SDL_SetRenderDrawColor(w.renderer, 0, 0, 0, 255);
    SDL_RenderClear(w.renderer);
    if (w.texture) {
      const SDL_Rect rect{0, 0, w.width, w.height};  // 1:1, no scaling
      SDL_RenderCopy(w.renderer, w.texture, nullptr, &rect);
    }
    SDL_RenderPresent(w.renderer);
  }
};

int LayerWindows::monitorCount() {
  if (!initVideo()) return 0;
  return std::max(0, SDL_GetNumVideoDisplays());
}

LayerWindows::LayerWindows(const std::vector<WindowRequest>& requests)
    : impl_(std::make_unique<Impl>()) {
  if (!initVideo()) throw sdlError("no display to show the layers on");
  const int monitors = SDL_GetNumVideoDisplays();
  for (const WindowRequest& r : requests) {
    if (r.fullScreen && (r.monitor < 0 || r.monitor >= monitors))
      throw RequestError(r.title + "_monitor", "monitor " + std::to_string(r.monitor) +
                                                   " does not exist (there are " +
                                                   std::to_string(monitors) + ")");
    Impl::Window w;
    SDL_Rect bounds{r.x, r.y, 64, 64};
    Uint32 flags = SDL_WINDOW_SHOWN;
    if (r.fullScreen) {
      SDL_GetDisplayBounds(r.monitor, &bounds);
      flags |= SDL_WINDOW_BORDERLESS;  // covers the monitor at its own resolution: 1:1 pixels
    }
    w.window = SDL_CreateWindow(("parallax: " + r.title).c_str(), bounds.x, bounds.y, bounds.w,
                                bounds.h, flags);
    if (!w.window) throw sdlError("cannot open a window");
    impl_->windows.push_back(w);  // owned from here, destroyed with the others
    Impl::Window& added = impl_->windows.back();
    added.renderer = SDL_CreateRenderer(added.window, -1, SDL_RENDERER_SOFTWARE);
    if (!added.renderer) throw sdlError("cannot draw in the window");
  }
}

LayerWindows::~LayerWindows() = default;

void LayerWindows::show(int index, const Image& picture) {
  impl_->setFrames(index, {&picture});  // no copy of the picture
}

void LayerWindows::showFrames(int index, const std::vector<Image>& frames) {
  std::vector<const Image*> pointers;
  for (const Image& frame : frames) pointers.push_back(&frame);
  impl_->setFrames(index, pointers);
}

void LayerWindows::Impl::setFrames(int index, const std::vector<const Image*>& frames) {
  Window& w = windows.at(size_t(index));
  clearFrames(w);
  if (frames.empty()) return;
  w.width = frames.front()->width();
  w.height = frames.front()->height();
  // Not every window system lets a window be smaller or larger than asked; the picture is
  // drawn 1:1 from the top-left corner whatever the window's size.
  if (!(SDL_GetWindowFlags(w.window) & SDL_WINDOW_BORDERLESS))
    SDL_SetWindowSize(w.window, w.width, w.height);
  std::vector<uint8_t> rgba(size_t(w.width) * size_t(w.height) * 4);
  for (const Image* frame : frames) {
    const Image& picture = *frame;
    if (picture.width() != w.width || picture.height() != w.height)
      throw std::invalid_argument("LayerWindows::showFrames: frames of different sizes");
    SDL_Texture* texture = SDL_CreateTexture(w.renderer, SDL_PIXELFORMAT_RGBA32,
                                             SDL_TEXTUREACCESS_STATIC, w.width, w.height);
    if (!texture) throw sdlError("cannot make the picture's texture");
    w.frames.push_back(texture);
    for (size_t i = 0; i < picture.pixels().size(); ++i) {
      for (int c = 0; c < 3; ++c)
        rgba[4 * i + size_t(c)] = uint8_t(
            std::lround(255.0f * linearToSrgb(std::clamp(picture.pixels()[i][c], 0.0f, 1.0f))));
      rgba[4 * i + 3] = 255;
    }
    SDL_UpdateTexture(texture, nullptr, rgba.data(), w.width * 4);
  }
  w.texture = w.frames.front();
  present(w);
}

void LayerWindows::streamFrames(int index, int width, int height, FrameSource next) {
  Impl::Window& w = impl_->windows.at(size_t(index));
  Impl::clearFrames(w);
  w.width = width;
  w.height = height;
  if (!(SDL_GetWindowFlags(w.window) & SDL_WINDOW_BORDERLESS))
    SDL_SetWindowSize(w.window, width, height);
  SDL_Texture* texture = SDL_CreateTexture(w.renderer, SDL_PIXELFORMAT_RGB24,
                                           SDL_TEXTUREACCESS_STREAMING, width, height);
  if (!texture) throw sdlError("cannot make the stream's texture");
  w.frames.push_back(texture);
  w.texture = texture;
  w.stream = std::move(next);
  if (Impl::nextStreamed(w)) impl_->present(w);
}

LayerWindows::Mode LayerWindows::monitorMode(int index) const {
  const Impl::Window& w = impl_->windows.at(size_t(index));
  Mode mode;
  SDL_DisplayMode current;
  const int display = SDL_GetWindowDisplayIndex(w.window);
  if (display >= 0 && SDL_GetCurrentDisplayMode(display, &current) == 0)
    mode = {current.w, current.h, current.refresh_rate};
  return mode;
}

long LayerWindows::run(const std::function<bool(ShowKey)>& onKey, double exitAfterSeconds,
                       const std::vector<ShowKey>& scriptedKeys, double framePeriodSeconds) {
  long presented = 0;
  for (const ShowKey key : scriptedKeys)
    if (!onKey(key)) return presented;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  long shownFrame = -1;
  double nextStreamDue = framePeriodSeconds;  // the first streamed frame is up already
  for (;;) {
    SDL_Event event;
    while (SDL_PollEvent(&event)) {
      if (event.type == SDL_QUIT) return presented;
      if (event.type == SDL_WINDOWEVENT && event.window.event == SDL_WINDOWEVENT_CLOSE)
        return presented;
      if (event.type == SDL_KEYDOWN && !onKey(keyOf(event.key.keysym.sym))) return presented;
    }
    bool streams = false;
    for (const Impl::Window& w : impl_->windows) streams |= bool(w.stream);
    if (framePeriodSeconds > 0 && streams) {
      if (elapsed() >= nextStreamDue) {
        for (Impl::Window& w : impl_->windows)
          if (w.stream && !Impl::nextStreamed(w)) return presented;
        // Late: the clock starts again from this frame.
        nextStreamDue = std::max(nextStreamDue + framePeriodSeconds, elapsed());
      }
    } else if (framePeriodSeconds > 0) {
      // Frame k from k periods after the start: the windows' frames k together.
      const long frame = long(elapsed() / framePeriodSeconds);
      if (frame != shownFrame) {
        for (Impl::Window& w : impl_->windows)
          if (!w.frames.empty()) w.texture = w.frames[size_t(frame) % w.frames.size()];
        shownFrame = frame;
      }
    }
    // Redraw: a window system may have dropped the picture (exposed, moved, another monitor).
    for (Impl::Window& w : impl_->windows) impl_->present(w);
    ++presented;
    if (exitAfterSeconds > 0 && elapsed() >= exitAfterSeconds) return presented;
    if (framePeriodSeconds > 0) {
      // Until the next frame is due (at most 30 ms, for the keys).
      const double due = streams ? nextStreamDue : double(shownFrame + 1) * framePeriodSeconds;
      const double next = due - elapsed();
      SDL_Delay(Uint32(std::clamp(next * 1000.0, 0.0, 30.0)));
    } else {
      SDL_Delay(30);
    }
  }
}

}  // namespace parallax
