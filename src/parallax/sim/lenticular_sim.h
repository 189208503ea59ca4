// What an eye sees on a slanted lenticular display (docs/lenticular.md, "The optics" and "Seeing
// the display"), under the design's lens optics (display/lenticular.h, LensOptics): at each point
// of the panel the eye looks through one lens toward the view fraction whose light from there
// reaches it (lensFractionSeen: parallel or converging bundles), and sees the subpixels under
// that lens weighted by the focal spot (lensSpotWeight). Beyond the cone the fraction wraps: the
// eye sees the neighbouring lens's views, the repeat zones of these displays.
#pragma once

#include <vector>

#include "parallax/display/lenticular.h"
#include "parallax/image/image.h"

namespace parallax {

// The view of `panel` (the panel's framebuffer, linear RGB, screenW x screenH) from an eye at
// eyeMm (display mm, z > 0), at the panel's resolution and as the viewer sees it (row 0 at the
// top, x to the viewer's right; flipped panels are mirrored back). Output pixel p: through the
// lens at p, the eye's view f_e; the subpixels of p's row under that lens, each weighted by the
// spot for its view's wrapped distance from f_e, summed per channel and scaled by 3 over the total
// weight (a subpixel lights a third of a pixel); where a lens's edge crosses p, the two lenses'
// colours weighted by the part of p's width each covers, so that every lens counts by its width
// (at p's centre alone a lens would count by the pixel centres it holds, and on a Portrait those
// go with the colour it shows the centre eye). Horizontal parallax only: the eye's height
// does not change what it sees. To read the panel under other optics, pass
// withOptics(design, optics).
// Throws InputError naming the calibration and "/screenW" when the panel's size differs, and
// std::invalid_argument for an eye not in front of the panel.
// `subpixels`: the panel's table (lenticularSubpixels), made once for many eyes; none: made here.
struct LenticularSubpixels;
Image simulateLenticularView(const LenticularDesign& design, const Image& panel, const Vec3d& eyeMm,
                             const LenticularSubpixels* subpixels = nullptr);

// What the simulator looks up for every eye: each subpixel's view fraction and where it sits
// along its row (x, mm), row by row (3 screenW a row), and how views run along a row.
struct LenticularSubpixels {
  std::vector<float> fraction, positionMm;
  double viewsPerWidth = 0;  // the view's change across one subpixel: +-1 / subpixelsPerLens
  double pixelStepMm = 0;    // from one pixel to the next along a row (negative when mirrored)
};
LenticularSubpixels lenticularSubpixels(const LenticularDesign& design);

// What an eye resolves of a view: one lens along a row, and along a column the rows over which
// the slanted lenses cycle the three colours (|slope| rows: each row moves the lens's phase by
// 1 / |slope| of a pixel's three subpixels). The dense measure compares views at this
// resolution, so that a narrow spot's colour stripes count as the eye mixes them.
Image lenticularAtDisplayResolution(const LenticularDesign& design, const Image& image);

}  // namespace parallax
