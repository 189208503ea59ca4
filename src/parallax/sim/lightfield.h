// The two-plane ray space of a display (the paper's section 2.4, Figs. 7 and 8): every display
// ray is one point (x, v), x where it crosses the image layer and v where it crosses the mask
// layer, in display millimetres. The plot shows the display's physical rays (the camera's
// virtual gap and distance, section 2.3, are ignored), one image row, one stretch of x.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "parallax/display/display.h"
#include "parallax/display/view_filter.h"

namespace parallax {

struct LightFieldOptions {
  double fromMm = -5.0, toMm = 5.0;  // stretch of the display (x on the image layer) to plot
  int row = -1;                      // image row (default: the middle row)
  int samplesPerPixel = 0;  // n * n > 0: also draw the n x n sub-ray samples of each cell (Fig. 8)
  ViewFilter filter;        // how the sub-rays spread in angle, as `render --filter`
  double widthPx = 900, heightPx = 600;
};

// One ray of the plot. Its cell is one film column wide in x, centred on the column, and one
// slit period wide in v, centred on the serving aperture.
struct LightFieldRay {
  double x = 0, v = 0;   // mm on the image and the mask layer
  int64_t aperture = 0;  // serving aperture (column of the mask)
  int column = 0;        // film column (image pixel, or subpixel in subpixel mode)
  int view = 0;          // the display's viewIndex of the column (DisplayModel::viewIndex)
};

// The central ray (u = 0.5) of every film column whose centre lies in [fromMm, toMm], left to
// right. Throws InputError (file "<light field>") for an empty stretch, a row off the panel or
// samplesPerPixel that is not a square.
std::vector<LightFieldRay> lightFieldRays(const DisplayDesign& design,
                                          const LightFieldOptions& options);
// The sub-ray samples of the same columns, samplesPerPixel per column in column order: sample
// i lies in x stratum i mod n of the column and aperture stratum i div n of the slit period,
// jittered within the stratum from a fixed seed. Empty for samplesPerPixel = 0.
std::vector<LightFieldRay> lightFieldSamples(const DisplayDesign& design,
                                             const LightFieldOptions& options);

// The plot as a standalone SVG document: the cells, the band of rays that reach the view zone,
// the central rays (coloured by view), the samples, axes in mm, a title and a legend.
std::string lightFieldSvg(const DisplayDesign& design, const LightFieldOptions& options);

}  // namespace parallax
