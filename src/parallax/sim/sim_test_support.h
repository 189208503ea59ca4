// Shared by the sim module's tests.
#pragma once

#include "parallax/display/display.h"

namespace parallax {

// Both layer orders, for the tests that check each.
inline constexpr LayerOrder kLayerOrders[] = {LayerOrder::BarrierBack, LayerOrder::BarrierFront};

// The built-in display at a small resolution, in either layer order.
inline DisplayDesign smallDisplay(LayerOrder order, int width = 180, int height = 24) {
  DisplaySpec s = defaultDisplaySpec();
  s.order = order;
  s.imagePanel.width = s.maskPanel.width = width;
  s.imagePanel.height = s.maskPanel.height = height;
  return designDisplay(s);
}

}  // namespace parallax
