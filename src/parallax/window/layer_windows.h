// Windows that show layer pictures on real panels, one pixel of the picture on one pixel of the
// panel (SDL2, the only user of it, behind this file). Full screen on a chosen monitor for the
// panels; plain windows side by side for a look (and for tests under a virtual X server).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "parallax/image/image.h"

namespace parallax {

struct WindowRequest {
  std::string title;       // a lower-case word ("image", "mask"): the request field TITLE_monitor
  int monitor = 0;         // SDL's display index; full screen there
  bool fullScreen = true;  // false: a plain window at (x, y) on the first monitor
  int x = 0, y = 0;
};

// Keys the viewer acts on; everything else is Other.
enum class ShowKey { Next, Previous, Info, Quit, Other };

class LayerWindows {
 public:
  // Opens one window per request. Throws std::runtime_error with SDL's message when there is no
  // display to open them on, and RequestError naming the field TITLE_monitor ("image_monitor")
  // for a monitor that does not exist.
  explicit LayerWindows(const std::vector<WindowRequest>& requests);
  ~LayerWindows();
  LayerWindows(const LayerWindows&) = delete;
  LayerWindows& operator=(const LayerWindows&) = delete;

  // The monitors SDL sees (0 without a display).
  static int monitorCount();

  // Shows `picture` (linear RGB, drawn as sRGB 8-bit, 1:1 from the window's top-left corner) in
  // window `index`.
  void show(int index, const Image& picture);
  // Shows `frames` in window `index` one after another (run's framePeriodSeconds), all the
  // same size; every window's frame k is shown at once.
  void showFrames(int index, const std::vector<Image>& frames);

  // Frames made as they are shown (a quilt video interlaced on the fly): `next` fills the next
  // frame of window `index` (width x height RGB triples of 8-bit sRGB codes, row 0 at the top)
  // and returns false after the last. run() with framePeriodSeconds asks for one frame per
  // period; behind time, frames follow one another at once until it catches up (they are made
  // in order, never skipped).
  using FrameSource = std::function<bool(std::vector<uint8_t>& rgb)>;
  void streamFrames(int index, int width, int height, FrameSource next);

  // The size of the monitor window `index` is on, and its refresh rate in Hz (0: unknown).
  struct Mode {
    int width = 0, height = 0, refreshHz = 0;
  };
  Mode monitorMode(int index) const;

  // Handles events until `onKey` returns false, the windows are closed, or `exitAfterSeconds`
  // (> 0) have passed. `scriptedKeys` are handled first, as if pressed, in order. With
  // framePeriodSeconds > 0 the windows' frames advance together, frame k shown from k periods
  // after the start (frames are skipped, never slowed, when drawing falls behind). Returns the
  // number of frames presented.
  long run(const std::function<bool(ShowKey)>& onKey, double exitAfterSeconds,
           const std::vector<ShowKey>& scriptedKeys = {}, double framePeriodSeconds = 0);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace parallax
