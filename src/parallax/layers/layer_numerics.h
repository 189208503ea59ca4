// The numerics both layer solvers share (image_layer_solver.cpp, layer_factorization.cpp): the
// errors against the targets (linear light, sRGB, 16-bit codes), the images' arithmetic, the
// views of frames and the row buffers of the passes that run row by row. Internal to layers/.
#pragma once

#include <cstddef>
#include <vector>

#include "parallax/core/parallel.h"
#include "parallax/image/image.h"
#include "parallax/layers/layer_problem.h"

namespace parallax::layer_numerics {

// The view of one image and mask pair, whichever layer is in front.
Image viewOf(const SeenLayers& seen, const Image& image, const Image& mask, int threads);

// Every value into [0, 1] (not a number: 0).
void clampToUnit(Image& image);

// Running sums of squares are kept in kLanes lanes, added in lane order at the end.
constexpr int kLanes = 16;

// One eye's error E_e for its view `seen`, and optionally the residual dE_e/dV (what the
// adjoint takes) and the Gauss-Newton weights (E_e's curvature along V). In linear light
// E_e = 1/2 |V - t|^2 (residual V - t, weights 1); with TrainingView::encodingScale c > 0,
// E_e = 1/2 |S(V/c) - S(t/c)|^2, the dense measure's own squared error (residual
// S'(V/c)/c (S(V/c) - S(t/c)), weights (S'(V/c)/c)^2).
// eyeError on `count` values from offset `first` of the view: the error, and the residual and
// weights of those values (either may be null).
double eyeErrorRange(const TrainingView& v, const Vec3f* seen, size_t first, size_t count,
                     Vec3f* residual, Vec3f* weights);
double eyeError(const TrainingView& v, const Image& seen, Image* residual, Image* weights);

// a .* b.
Image elementwise(const Image& a, const Image& b);
// a += s * b over images of one size.
void addScaled(Image& a, const Image& b, float s);
// <a, b> over every rowStride-th row (the rows the image solver's plane step samples).
double dot(const Image& a, const Image& b, int rowStride = 1);

// The average view of the frames from one eye.
Image averageView(const TrainingView& v, const std::vector<LayerFrame>& frames, int threads);

// 1 / (view pixels x 3 x eyes): E's normaliser (layerObjective, SolveReport::objective).
double normaliser(const std::vector<TrainingView>& views);

// `boxedTargets`: whether the solver reads targets kept as B^T t (factorizeLayers with the
// image in front); elsewhere they are refused.
void checkViews(const std::vector<TrainingView>& views, bool boxedTargets = false);

// The gradient of one eye's view with respect to the image layer (imageLayer) or the mask,
// the other layer fixed: the front or the rear adjoint, by the display's layer order.
void addLayerGradient(const TrainingView& v, const Image& residual, const Image& other, Image& grad,
                      bool imageLayer, int threads);
void addImageGradient(const TrainingView& v, const Image& residual, const Image& mask, Image& grad,
                      int threads);

// The frames as the eyes see them: each frame's rear layer (the mask with the image in front)
// through the diffuser: `frames` themselves without one, else blurred copies kept in `holder`.
const std::vector<LayerFrame>& seenFrames(const std::vector<TrainingView>& views,
                                          const std::vector<LayerFrame>& frames,
                                          const RearDiffuser& diffuser, int threads,
                                          std::vector<LayerFrame>& holder);

// One worker's row buffers for the passes that run row by row (output row j of every eye's
// view depends on the front layer's row j only, and writes only its gradient's row j).
struct RowWork {
  explicit RowWork(int width)
      : seen(size_t(width)),
        residual(size_t(width)),
        weights(size_t(width)),
        other(size_t(width)),
        seenRear(size_t(width)) {}
  size_t first(int row) const { return size_t(row) * seen.size(); }
  std::vector<Vec3f> seen, residual, weights, other, seenRear;
  std::vector<Vec3f> frameMasks;  // factorizeLayers: every frame's seen mask row
  std::vector<Vec3f> eyeWeights;  // ImageLayerPasses::rowPass: every eye's W_e row
  std::vector<Vec3f> ones;        // ImageLayerPasses::rowPass: a row of 1 (the preconditioner)
  SeenLayers::RowScratch scratch;
};

// body(row, work) for every view row, in parallel, `grain` rows to a task; the rows' results
// (a double, or anything with +=) added in row order, so the sum is the same for any thread
// count.
template <class Result = double, class Body>
Result sumOverRows(const std::vector<TrainingView>& views, int threads, const Body& body,
                   int grain = 2) {
  const int width = views.front().seen.width(), rows = views.front().seen.height();
  std::vector<Result> perRow(size_t(rows), Result{});
  parallelFor(rows, threads, grain, [&](int64_t begin, int64_t end) {
    RowWork work(width);
    for (int64_t row = begin; row != end; ++row) perRow[size_t(row)] = body(int(row), work);
  });
  Result sum{};
  for (const Result& v : perRow) sum += v;
  return sum;
}

// Whether each image row is a problem of its own for optimizeImageLayer: with the image in
// front, output row j of every eye's view depends on the image's row j only (the mask fixed),
// so E is a sum of one term per row, each a function of its row alone.
bool rowsSeparable(const std::vector<TrainingView>& views);

}  // namespace parallax::layer_numerics
