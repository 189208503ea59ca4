// What one eye sees on a two-layer display as a bilinear function of the two layers, with its
// adjoints: the operator the layer solvers (layers/) fit layers with. It is the simulator's
// exact view (simulator.h: the product of the two layers' box pixels integrated over each output
// pixel; a pinhole eye or a pupil's average, through the panels' colour filters or not:
// SeenOptics; a diffuser's blur is the caller's, on the rear layer it passes) at the front
// layer's resolution, unnormalised (backlight 1; with colour filters, each filtered layer's 1/3
// undone as the simulator's normalisation does), followed by the box one screen period wide
// along x that the dense measure compares views through (atDisplayResolution):
//
//     V = B P(front, rear),   P(front, rear)[o] = sum over pieces k of o: w_k front[f_k] rear[r_k]
//
// Linear in each layer for the other fixed, so its adjoints give the gradient of
// 1/2 |V - target|^2 with respect to either layer.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "parallax/display/display.h"
#include "parallax/image/box_row.h"
#include "parallax/image/image.h"
#include "parallax/sim/view_pieces.h"

namespace parallax {

// A layer's rows as the operator reads them: row y starts at first + y stride. An Image, or
// the simulator's cells (each row followed by a dark cell: simulator.h), without a copy.
struct LayerRows {
  const Vec3f* first = nullptr;
  size_t stride = 0;
  int width = 0, height = 0;
  LayerRows(const Image& image)  // implicit: every Image is one
      : first(image.pixels().data()),
        stride(size_t(image.width())),
        width(image.width()),
        height(image.height()) {}
  LayerRows(const Vec3f* rowsFrom, size_t rowStride, int columns, int rows)
      : first(rowsFrom), stride(rowStride), width(columns), height(rows) {}
  const Vec3f* row(int y) const { return first + size_t(y) * stride; }
};

// What the operator models besides the layers' box pixels.
struct SeenOptics {
  bool periodBox = true;  // apply B (false: V = P, for tests and other measures)
  // The simulator's colour filters (SimulationOptions::colourFilters): a layer whose panel has
  // an RGB or BGR order is three vertical stripes a pixel, stripe c passing channel c only. The
  // stripes run down the columns, so they change the pieces across a row alone: channel c of
  // output pixel i meets the rear pixels under the front's stripe c that pass channel c, each
  // with its own weight (the weights per channel of Sight::acrossWeights).
  bool colourFilters = false;
  // With colourFilters: the rear layer comes as its stripe cells, three a pixel, already
  // filtered (and blurred: sim/diffuser.h, stripedDiffuserBlurred), so each cell passes what it
  // holds; the front layer's pixels pass through their stripes. For a diffuser, which blurs the
  // light the rear stripes pass.
  bool rearStripeCells = false;
  // The simulator's pupil (SimulationOptions::pupilDiameterMm, pupilSamples): the view is the
  // average of the pinhole views from pupilSamples points of a disk of this diameter around
  // the eye (pupilPoints, view_pieces.h). Each point is a sight with its own pieces; the rear
  // layer as the eye sees it is their average, m_j = 1/N sum_p m_j^p (output pixel i lies in
  // front pixel i from every point), so the split P_j = front_j .* m_j holds. 0: a pinhole eye.
  double pupilDiameterMm = 0;
  int pupilSamples = 16;
};

class SeenLayers {
 public:
  SeenLayers(const DisplayDesign& design, const Vec3d& eyeMm, const SeenOptics& optics = {});

  int width() const { return width_; }
  int height() const { return height_; }
  bool imageInFront() const { return imageInFront_; }
  const Vec3d& eye() const { return eye_; }
  // Whether every channel of a pixel is seen with the same weights (no colour filters on
  // either layer), so that a grey rear layer is seen grey (the solvers' one-float seen masks).
  bool seesGreyAsGrey() const { return seesGreyAsGrey_; }
  // The points the eye sees from: 1 for a pinhole eye, the pupil's samples otherwise.
  int sights() const { return int(sights_.size()); }

  // V for the layers as panel images (front and rear in the display's layer order).
  Image view(const LayerRows& front, const LayerRows& rear, int threads = 0) const;
  // gradFront += (dV/dfront)^T residual and gradRear += (dV/drear)^T residual: the gradient of
  // 1/2 |V - target|^2 for residual = V - target. Sized as the layers; the same result for any
  // thread count.
  void addFrontGradient(const Image& residual, const Image& rear, Image& gradFront,
                        int threads = 0) const;
  void addRearGradient(const Image& residual, const Image& front, Image& gradRear,
                       int threads = 0) const;
  // B and its transpose on a view-sized image.
  Image box(const Image& view, int threads = 0) const;
  Image boxTransposed(const Image& view, int threads = 0) const;

  // One row at a time, for solvers that fuse a view, its residual and its adjoint in one pass
  // over a row (layers/image_layer_solver.cpp): output row j depends on front row j only, and B
  // acts along rows, so rows are independent. The same arithmetic as view() and addFrontGradient(),
  // which are made of these. `scratch` is the caller's, one per worker.
  struct RowScratch {
    std::vector<Vec3f> product, filtered, seenRear;
    std::vector<Vec3f> rearRow;   // seenRearRow: the rear rows under front row j, blended
    std::vector<Vec3f> sightRow;  // seenRearRow: one sight's m_j, for a pupil's
    std::vector<Vec3f> planes;    // the rear stripe cells as three planes (Sight::stripeRuns)
    // keepBlends (the caller's promise that no rear layer it passes changes while this scratch
    // lives): seenRearRow keeps its last blend of each rear layer with the rows and weights it
    // was made of, and another eye whose row meets the same rear rows with the same weights
    // (every eye at one distance: their lines of sight differ along x only) takes it as it is.
    bool keepBlends = false;
    struct Blend {
      const Vec3f* rearFirst = nullptr;
      int sight = 0;
      std::vector<Piece> pieces;
      std::vector<Vec3f> rows;
      bool any = false;
    };
    std::vector<Blend> blends;
  };
  // V's row j into out[0 .. width()).
  void viewRow(const LayerRows& front, const LayerRows& rear, int j, Vec3f* out,
               RowScratch& scratch) const;
  // gradFront's row j += (dV_j/dfront)^T residual[0 .. width()).
  void addFrontGradientRow(const Vec3f* residual, const Image& rear, int j, Image& gradFront,
                           RowScratch& scratch) const;

  // The same row operators split at the rear layer: output pixel i of row j lies in front pixel
  // (i, j) alone (the views are at the front layer's resolution), so
  //     P(front, rear)_j = front_j .* m_j,   m_j[i] = sum over pieces k of (i, j): w_k rear[r_k],
  // the rear layer as the eye sees it through that front pixel. A solver whose rear layer is
  // fixed makes m_j once per eye and row and reuses it for every view and adjoint of the row.
  // m_j into seenRear[0 .. width()). The rear rows front row j meets are blended first (their
  // vertical weights), then resampled along the row once.
  void seenRearRow(const LayerRows& rear, int j, Vec3f* seenRear, RowScratch& scratch) const;
  // V_j = B (frontRow .* seenRear) into out (the row's front pixels frontRow[0 .. width())).
  void viewRowSeen(const Vec3f* frontRow, const Vec3f* seenRear, Vec3f* out,
                   RowScratch& scratch) const;
  // The same with a grey m_j (one value per pixel, for every channel: a grey mask's).
  void viewRowSeen(const Vec3f* frontRow, const float* greySeenRear, Vec3f* out,
                   RowScratch& scratch) const;
  // For the rear layer's gradient row by row (each rear row gathers from the output rows that
  // meet it, so rear rows in parallel write disjoint rows): the output rows whose pieces meet
  // rear row r with those pieces' vertical weights and their sight, sight by sight, in order;
  struct RearSource {
    int outputRow = 0;
    float weight = 0;
    int sight = 0;
    bool operator==(const RearSource&) const = default;
  };
  const std::vector<RearSource>& rearRowSources(int r) const { return rearRowSources_[size_t(r)]; }
  // B^T on one output row (filtered[0 .. width()), which it overwrites);
  void boxTransposedRowInto(const Vec3f* residual, Vec3f* filtered) const;
  // and gradRearRow[p.rear] += weight w_a front(i, j) filtered[i] over the across pieces a of
  // each output column i of row j: output row j's share of a rear row whose vertical piece has
  // `weight` (rearRowSources), seen from `sight`. addRearGradient is made of these.
  void addRearGradientFromRow(const Vec3f* filtered, const Image& front, int j, float weight,
                              Vec3f* gradRearRow, int sight = 0) const;
  // gradRow[i] += seenRear[i] (B^T residual)[i]: front row j's gradient.
  void addFrontGradientRowSeen(const Vec3f* residual, const Vec3f* seenRear, Vec3f* gradRow,
                               RowScratch& scratch) const;
  void addFrontGradientRowSeen(const Vec3f* residual, const float* greySeenRear, Vec3f* gradRow,
                               RowScratch& scratch) const;

 private:
  DisplayDesign design_;
  Vec3d eye_;
  bool imageInFront_ = true, periodBox_ = true, seesGreyAsGrey_ = true;
  int width_ = 0, height_ = 0, frontColumns_ = 0, frontRows_ = 0, rearColumns_ = 0, rearRows_ = 0;
  // The pieces across in runs for vectorised loops: the eye sees rear cells at the front's
  // pitch times the gap's small stretch, so nearly every column i meets rear cells i + s and
  // i + s + 1 (weights first, second; second 0 for one piece), with the shift s constant over
  // hundreds of columns. A run is such a stretch of columns with one shift; the weights are
  // per float of the row (three per column). Columns of any other form (the row's ends, a rear
  // layer of another pitch) are `unevenColumns`, read through their pieces.
  struct AcrossRun {
    int begin = 0, end = 0, shift = 0;
  };
  // What one point of the eye sees: the pieces across in front and rear pixels (front == the
  // output column) with their weights per channel in acrossWeights (all three the piece's
  // weight without colour filters; times 1/N for a pupil's N points), and down.
  struct Sight {
    std::vector<Piece> across, down;
    std::vector<Vec3f> acrossWeights;
    std::vector<uint32_t> acrossStart, downStart;
    std::vector<AcrossRun> acrossRuns;
    std::vector<float> acrossFirst, acrossSecond;
    // Rear stripe cells (SeenOptics::rearStripeCells) are three a front pixel, so a column
    // meets four or five of them: columns i whose pieces are the cells 3i + s + m (m below
    // kStripeTerms) go in runs of one s, which read the blended cells as three planes (plane q:
    // the cells 3i' + q), term m a shifted read of plane (s + m) mod 3 with its weights per
    // float (stripeWeights, kStripeTerms rows of 3 width floats).
    std::vector<AcrossRun> stripeRuns;
    std::vector<float> stripeWeights;
    std::vector<int> unevenColumns;
  };
  static constexpr int kStripeTerms = 5;
  bool rearStripeCells_ = false;
  std::vector<Sight> sights_;
  void makeFilteredPieces(Sight& sight, int frontStripes, int rearStripes, const Panel& front,
                          const Panel& rear, double u0, double du) const;
  void makeAcrossRuns(Sight& sight) const;
  // The stripe runs' reads and their transpose (Sight::stripeRuns) on a row of cells.
  void gatherStripeRuns(const Sight& sight, const Vec3f* cells, Vec3f* out,
                        std::vector<Vec3f>& planes) const;
  void scatterStripeRuns(const Sight& sight, const Vec3f* filtered, const Vec3f* frontRow,
                         float weight, Vec3f* cells) const;
  // One sight's m_j (seenRearRow).
  void sightRearRow(const Sight& sight, int s, const LayerRows& rear, int j, Vec3f* seenRear,
                    RowScratch& scratch) const;
  // For each rear row, the output rows whose pieces meet it, those pieces' weights and sights.
  std::vector<std::vector<RearSource>> rearRowSources_;
  // B, the box of one screen period along x (image/box_row.h).
  BoxRow box_;
  const Vec3f* boxTransposedInScratch(const Vec3f* residual, RowScratch& scratch) const;
};

}  // namespace parallax
