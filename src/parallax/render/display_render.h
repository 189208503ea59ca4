// Rendering for a display of any kind (display/display_model.h): the panel's picture through
// the display camera, and the mask layer's raster for kinds that have one.
#pragma once

#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/display/display.h"
#include "parallax/display/display_model.h"
#include "parallax/display/view_filter.h"
#include "parallax/image/image.h"
#include "parallax/render/render.h"
#include "parallax/scene/scene.h"

namespace parallax {

struct DisplayLayers {
  Image image;  // the panel's picture (a barrier's image layer), linear RGB, panel resolution
  Image mask;   // each mask pixel's open fraction by area (grey, linear); empty without a mask
  RenderStats stats;
};

// The settings renderDisplay renders `display` with: one sample per film pixel when every sample
// is its central ray (display.centralRayOnly(): the view filter none), since more would trace
// the same ray again; `settings` otherwise.
RenderSettings displayRenderSettings(const DisplayModel& display, RenderSettings settings);

// The film of the display camera folded into the panel: with subpixel columns each film column
// keeps only its own colour channel (panelFromSubpixelFilm).
DisplayLayers renderDisplay(const Scene& scene, const Accelerator& accelerator,
                            const DisplayModel& display, const RenderSettings& settings,
                            const ProgressCallback& progress = {});
// A barrier design; `filter`: how each pixel's sub-rays spread in angle (display/view_filter.h).
DisplayLayers renderDisplay(const Scene& scene, const Accelerator& accelerator,
                            const DisplayDesign& design, const RenderSettings& settings,
                            const ProgressCallback& progress = {}, const ViewFilter& filter = {});

// The usual practice the paper improves on (its Fig. 2): render one ordinary picture per view
// from that view's design eye position (one-axis perspective for horizontal-parallax displays),
// then interleave them, each film column taking its own view's picture at its own place.
DisplayLayers renderDirectMapping(const Scene& scene, const Accelerator& accelerator,
                                  const DisplayModel& display, const RenderSettings& settings,
                                  const ProgressCallback& progress = {});
DisplayLayers renderDirectMapping(const Scene& scene, const Accelerator& accelerator,
                                  const DisplayDesign& design, const RenderSettings& settings,
                                  const ProgressCallback& progress = {});

// Interleaves per-view pictures (each at the panel's resolution) into the panel's picture.
Image interleaveViews(const DisplayModel& display, const std::vector<Image>& views);
Image interleaveViews(const DisplayDesign& design, const std::vector<Image>& views);

}  // namespace parallax
