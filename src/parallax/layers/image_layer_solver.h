// optimizeImageLayer: the image layer for a fixed mask (layer_problem.h, the problem; the
// method in docs/content-adaptive.md).
#pragma once

#include <vector>

#include "parallax/image/image.h"
#include "parallax/layers/layer_problem.h"

namespace parallax {

// The image layer for the fixed `mask`, starting from `image` (clamped to [0, 1]). With the
// image in front (the barrier behind it) each image row is a problem of its own (row j of every
// view depends on the image's row j only) and is solved on its own, all its iterations in one
// task with its own steps (docs/content-adaptive.md, "Each row its own problem").
Image optimizeImageLayer(const std::vector<TrainingView>& views, Image image, const Image& mask,
                         int iterations, int threads = 0, SolveReport* report = nullptr,
                         const SolveProgress& progress = {}, const RearDiffuser& diffuser = {});

// optimizeImageLayer with the targets made a band of rows at a time, as the solve reaches them
// (the image in front, sRGB errors: each image row is a problem of its own; the display's box
// along rows only): `targets(firstRow, rows, views)` sets every view's encodedTarget to rows
// [firstRow, firstRow + rows) of its target (and firstTargetRow to firstRow), bands of
// `bandRows` rows from the top. The same layers and report as optimizeImageLayer on the whole
// targets, holding one band's targets at a time instead of every eye's whole view.
using BandTargets = std::function<void(int firstRow, int rows, std::vector<TrainingView>& views)>;
Image optimizeImageLayerByBands(std::vector<TrainingView>& views, const BandTargets& targets,
                                int bandRows, Image image, const Image& mask, int iterations,
                                int threads = 0, SolveReport* report = nullptr,
                                const SolveProgress& progress = {},
                                const RearDiffuser& diffuser = {});

namespace detail {
// E's Gauss-Newton curvatures on the plane of the descent direction d and the previous step p:
// sum_e <A_e u, A_e v>_{W_e} for (u, v) = (d, d), (d, p), (p, p); those with p, and (d, d)
// again (`ddSampled`), on the sampled rows only (planeRowStride).
struct Curvatures {
  double dd = 0, dp = 0, pp = 0, ddSampled = 0;
  Curvatures& operator+=(const Curvatures& o) {
    dd += o.dd, dp += o.dp, pp += o.pp, ddSampled += o.ddSampled;
    return *this;
  }
};

// optimizeImageLayer's step, for the tests: the step a d + b p that minimises E's Gauss-Newton
// model
//   E + a <g, d> + b <g, p> + (a^2 dd + 2 a b dp + b^2 pp) / 2
// on the plane of d and p (for a quadratic E, the conjugate-gradient step: the previous step
// carries what steepest descent would zig-zag back to), or along d alone (a = -<g, d> / dd,
// b = 0) where the plane is degenerate: no previous step, or p nearly parallel to d.
struct PlaneStep {
  double a = 0, b = 0;
};
PlaneStep planeStep(double gd, double gp, Curvatures h);

// The sRGB encoding S(x) of x clamped to [0, 1] and its slope S'(x) as the solvers compute them
// against encoded targets (layer_numerics.cpp, vectorised arithmetic), for the tests.
void srgbEncode(float x, float& encoded, float& slope);

// optimizeImageLayer with whole-image steps, its passes eye by eye over whole images, as it runs
// with the barrier in front; with the image in front it solves each row on its own, every eye
// in one pass over the row (image_layer_solver.cpp, RowSolves). For the tests: on a problem whose
// other rows are solved already, both must give the same row.
Image optimizeImageLayerByEye(const std::vector<TrainingView>& views, Image image,
                              const Image& mask, int iterations, int threads = 0,
                              SolveReport* report = nullptr, const RearDiffuser& diffuser = {});
}  // namespace detail

}  // namespace parallax
