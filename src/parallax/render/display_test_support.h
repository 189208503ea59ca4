// Shared by the render tests: a crop of the built-in display (0.2745 mm pixels, g = 3 mm,
// 9 views, D = 600 mm) small enough to render in milliseconds.
#pragma once

#include "parallax/display/display.h"

namespace parallax {

inline DisplaySpec smallDisplaySpec(int width = 180, int height = 60,
                                    LayerOrder order = LayerOrder::BarrierBack) {
  DisplaySpec s = defaultDisplaySpec();
  s.order = order;
  s.imagePanel.width = s.maskPanel.width = width;
  s.imagePanel.height = s.maskPanel.height = height;
  return s;
}

}  // namespace parallax
