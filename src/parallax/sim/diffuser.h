// The diffuser foil between the two panels (the paper's prototype kept one, section 3.1): a
// Gaussian blur of the rear layer, the one model the simulator sees it with and the layer
// solvers solve for it with.
//
// The rear panel's box pixels are blurred with a Gaussian of standard deviation sigma; each
// cell keeps the blurred value at its centre, so the weight of a neighbour m cells away is the
// Gaussian's mass over that cell, [m - 1/2, m + 1/2] (cells beyond the panel are dark). Across
// then down, separably. The operator G is symmetric (its weights depend on |m| only, and a
// cell beyond the panel contributes nothing either way), so G is its own transpose: the
// solvers' adjoint of "blur the rear layer" is the same blur.
#pragma once

#include <cstddef>

#include "parallax/core/math.h"
#include "parallax/display/display.h"
#include "parallax/image/image.h"

namespace parallax {

// Blurs `rows` rows of `columns` cells, each row `stride` cells after the previous (cells past
// `columns` are left alone), with sigma given in cells across and down; 0 leaves that axis.
void diffuserBlur(Vec3f* cells, int columns, int rows, size_t stride, double sigmaCellsX,
                  double sigmaCellsY, int threads = 0);

// An image of a panel whose pixels are pitchMm apart, blurred by a diffuser of sigmaMm (a copy;
// the image itself when sigmaMm is 0).
Image diffuserBlurred(const Image& layer, double sigmaMm, double pitchMm, int threads = 0);

// A rear layer seen through its colour filters and then the diffuser (simulator.h: the foil
// blurs the light the stripes pass, so the stripes come first): S, three cells a pixel, cell
// 3x + s holding the channel stripe s passes (view_pieces.h, stripePasses) times 3 (the stripe's
// 1/3 undone, as SeenLayers' filtered pieces undo it), blurred with sigma in cells (a third of
// the pitch across, the pitch down): G S, an image three times as wide, which SeenLayers reads
// as its rear layer's cells (SeenOptics::rearStripeCells). Its transpose S^T G^T = S^T G takes a
// gradient of those cells back to the pixels: pixel x's channel c is 3 times its stripe's cell.
Image stripedDiffuserBlurred(const Image& layer, SubpixelOrder order, double sigmaMm,
                             double pitchMm, int threads = 0);
Image stripedDiffuserBlurredTransposed(const Image& cells, SubpixelOrder order, double sigmaMm,
                                       double pitchMm, int threads = 0);

}  // namespace parallax
