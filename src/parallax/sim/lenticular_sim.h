// What an eye sees on a slanted lenticular display (docs/lenticular.md, "Seeing the display").
// Each lens sends the light of a subpixel into the direction of the subpixel's view fraction f,
// the horizontal angle (f - 1/2) * viewCone (display/lenticular.h). An eye at horizontal angle
// theta from a lens therefore sees, through that lens, the subpixels whose view is
// f_e = theta / viewCone + 1/2, wrapped into [0, 1): beyond the cone it sees the neighbouring
// lens's views, the repeat zones of these displays.
#pragma once

#include "parallax/display/lenticular.h"
#include "parallax/image/image.h"

namespace parallax {

// The view of `panel` (the panel's framebuffer, linear RGB, screenW x screenH) from an eye at
// eyeMm (display mm, z > 0), at the panel's resolution and as the viewer sees it (row 0 at the
// top, x to the viewer's right; flipped panels are mirrored back). Output pixel p, channel c:
// the eye's view f_e at p, taken in the lens around p (the unwrapped view nearest p's own), is
// bracketed by two channel-c subpixels of p's row, and their values are interpolated linearly in
// view: a triangular weight 1 - |f - f_e| / s, s the view step between neighbouring subpixels of
// one channel (pitch_px / screenW). Horizontal parallax only: the eye's height does not change
// what it sees.
// Throws InputError naming the calibration and "/screenW" when the panel's size differs, and
// std::invalid_argument for an eye not in front of the panel.
Image simulateLenticularView(const LenticularDesign& design, const Image& panel,
                             const Vec3d& eyeMm);

}  // namespace parallax
