// Rendering for a slanted lenticular display: the panel's framebuffer, one ray per subpixel
// (camera/lenticular_camera.h, docs/lenticular.md).
#pragma once

#include "parallax/accel/accelerator.h"
#include "parallax/display/lenticular.h"
#include "parallax/image/image.h"
#include "parallax/render/render.h"
#include "parallax/scene/scene.h"

namespace parallax {

struct LenticularRender {
  Image image;  // the panel's framebuffer, linear RGB, screenW x screenH
  RenderStats stats;
};

// Each subpixel is rendered along its own rays and keeps only its own colour channel; the panel
// sits where the scene's display placement puts it (its width from DPI). `filter` spreads a
// subpixel's rays around its view (LenticularCamera).
LenticularRender renderLenticular(const Scene& scene, const Accelerator& accelerator,
                                  const LenticularDesign& design, const RenderSettings& settings,
                                  const ProgressCallback& progress = {},
                                  const ViewFilter& filter = {});

}  // namespace parallax
