// Rendering for the display: the image layer through the parallax-barrier camera, and the
// mask layer's raster.
#pragma once

#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/display/display.h"
#include "parallax/display/view_filter.h"
#include "parallax/image/image.h"
#include "parallax/render/render.h"
#include "parallax/scene/scene.h"

namespace parallax {

struct DisplayLayers {
  Image image;  // the interleaved picture, linear RGB, at the image layer's resolution
  Image mask;   // each mask pixel's open fraction by area (grey, linear transmittance)
  RenderStats stats;
};

// `filter`: how each pixel's sub-rays spread in angle (display/view_filter.h).
DisplayLayers renderDisplay(const Scene& scene, const Accelerator& accelerator,
                            const DisplayDesign& design, const RenderSettings& settings,
                            const ProgressCallback& progress = {}, const ViewFilter& filter = {});

// The usual practice the paper improves on (its Fig. 2): render one ordinary picture per view
// from that view's design eye position (one-axis perspective for slits), then interleave them,
// each image pixel (or subpixel column) taking its own view's picture at its own place.
DisplayLayers renderDirectMapping(const Scene& scene, const Accelerator& accelerator,
                                  const DisplayDesign& design, const RenderSettings& settings,
                                  const ProgressCallback& progress = {});

// Interleaves per-view pictures (each at the image layer's resolution) into the image layer.
Image interleaveViews(const DisplayDesign& design, const std::vector<Image>& views);

}  // namespace parallax
