// Without a display, showing refuses in one clear message instead of "showing" the layers on
// SDL's offscreen fallback (the Xvfb test in tests/cli_show_test.sh covers a real display).
#include "parallax/window/layer_windows.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace parallax {
namespace {

TEST(LayerWindows, WithoutADisplayThereIsNoMonitorAndNoWindow) {
  ::unsetenv("DISPLAY");
  ::unsetenv("WAYLAND_DISPLAY");
  ::unsetenv("SDL_VIDEODRIVER");
  EXPECT_EQ(LayerWindows::monitorCount(), 0);
  try {
    LayerWindows windows({{"image", 0, false, 0, 0}});
    FAIL() << "a window opened without a display";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no display to show the layers on"), std::string::npos);
  }
}

}  // namespace
}  // namespace parallax
