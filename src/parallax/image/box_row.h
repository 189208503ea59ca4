// The box one screen period wide along a row, through which the dense measure compares views
// (docs/simulator.md, "Quality figures"): output column x is the mean of the row's box pixels over
// its window [x + a, x + b], a = 1/2 - w/2, b = 1/2 + w/2, clipped to the row and renormalised at
// its ends. One implementation for boxFilterX (image/metrics.h) and the layer solvers' operator B
// and its transpose (sim/seen_layers.h).
#pragma once

#include <vector>

#include "parallax/core/math.h"

namespace parallax {

// Whether CPUs with AVX-512 run the stencil's shifted-vector loop (box_row.cpp, the same sums as
// the plain one), for the test that holds the two to the same bits; returns the previous
// setting. On by default.
bool allowShiftedStencil(bool allow);

class BoxRow {
 public:
  // Widths up to this many taps run as a stencil with the taps in registers.
  static constexpr int kMostTaps = 16;

  BoxRow() = default;
  // A row of `columns` pixels, the box `widthPx` pixels wide (> 0).
  BoxRow(int columns, double widthPx);

  int columns() const { return columns_; }
  int tapCount() const { return int(taps_.size()); }
  // B: out[x] = the window's mean (in and out may not alias; both hold columns() pixels).
  void apply(const Vec3f* in, Vec3f* out) const;
  // B^T: pixel k receives sum_x in[x] |[k, k+1] n window_x| / |window_x|.
  void applyTransposed(const Vec3f* in, Vec3f* out) const;

 private:
  int columns_ = 0;
  double a_ = 0, b_ = 0;
  // Where the window lies inside the row (columns [interiorBegin_, interiorEnd_)) B is a
  // stencil of fixed taps: out[x] = sum_d tap_d in[x + d], d from firstTap_,
  // tap_d = |[d, d+1] n [a, b]| / w.
  int firstTap_ = 0, interiorBegin_ = 0, interiorEnd_ = 0;
  std::vector<float> taps_;
  // The columns whose window the row clips (outputs of B, and inputs of B^T whose windows are
  // not all interior), made once: each one's terms (the pixel or output read, and its weight),
  // summed in double in this order. B: the overlaps |[k, k+1] n window_x|, the sum divided by
  // the clipped window's length; B^T: overlap / length per term.
  struct EdgeTerm {
    int from;
    double weight;
  };
  struct EdgeColumn {
    int column;
    double length;  // B: the clipped window's length; B^T: 1
    std::vector<EdgeTerm> terms;
  };
  std::vector<EdgeColumn> edges_, transposedEdges_;
  // out[column] = the sum of weight x in[from] over each column's terms, over its length.
  static void edgeSums(const std::vector<EdgeColumn>& columns, const Vec3f* in, Vec3f* out);
  // Where B^T's stencil runs: pixels [transposedBegin_, transposedEnd_).
  int transposedBegin_ = 0, transposedEnd_ = 0;
  // Output x's window clipped to the row, [lo, hi].
  double windowLo(int x) const;
  double windowHi(int x) const;
  void makeEdges();
};

}  // namespace parallax
