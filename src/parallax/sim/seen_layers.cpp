#include "parallax/sim/seen_layers.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "parallax/core/lane_kernel.h"
#include "parallax/core/parallel.h"

namespace parallax {

namespace {

template <class Body>
void forEachRow(int rows, int threads, const Body& body) {
  parallelFor(rows, threads, 8, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row != end; ++row) body(int(row));
  });
}

void checkLayer(const LayerRows& layer, int columns, int rows, const char* what) {
  if (layer.width != columns || layer.height != rows)
    throw std::invalid_argument(std::string("SeenLayers: the ") + what +
                                " layer's size differs from its panel");
}

}  // namespace

SeenLayers::SeenLayers(const DisplayDesign& design, const Vec3d& eye, const SeenOptics& optics)
    : design_(design), eye_(eye), periodBox_(optics.periodBox) {
  const DisplaySpec& spec = design.spec;
  imageInFront_ = spec.order == LayerOrder::BarrierBack;
  const Panel& front = imageInFront_ ? spec.imagePanel : spec.maskPanel;
  const Panel& rear = imageInFront_ ? spec.maskPanel : spec.imagePanel;
  frontColumns_ = width_ = front.width;
  frontRows_ = height_ = front.height;
  const bool rearCells = optics.colourFilters && optics.rearStripeCells;
  rearStripeCells_ = rearCells;
  rearColumns_ = rear.width * (rearCells ? 3 : 1);
  rearRows_ = rear.height;
  const double rearCellMm = rear.pitchMm / (rearCells ? 3 : 1);
  // Stripes per pixel of each layer (simulator.cpp's makeLayer).
  const auto stripes = [&](const Panel& panel) {
    return optics.colourFilters && panel.subpixels != SubpixelOrder::None ? 3 : 1;
  };
  const int frontStripes = stripes(front), rearStripes = rearCells ? 1 : stripes(rear);
  seesGreyAsGrey_ = frontStripes == 1 && rearStripes == 1 && !rearCells;
  const std::vector<Vec3d> points = pupilPoints(eye, optics.pupilDiameterMm, optics.pupilSamples);
  const float share = 1.0f / float(points.size());  // each sight's share of the average
  const double frontWidth = front.widthMm(), frontHeight = front.heightMm();
  rearRowSources_.assign(size_t(rearRows_), {});
  for (const Vec3d& point : points) {
    Sight& sight = sights_.emplace_back();
    // The simulator's geometry (DisplaySimulator::view): x across the front layer is
    // (t - 1/2) frontWidth, and the line from the point through it meets the rear layer
    // stretched by (e.z + g) / e.z about the point.
    const double stretch = (point.z + design.gapMm) / point.z;
    const auto column = [&](double t) {
      const double rearX = point.x + ((t - 0.5) * frontWidth - point.x) * stretch;
      return (rearX + 0.5 * rear.widthMm()) / rearCellMm;
    };
    if (seesGreyAsGrey_) {
      piecesAlongAxis(width_, frontColumns_, rearColumns_, column(0), column(1) - column(0), 0, -1,
                      sight.across, sight.acrossStart);
      sight.acrossWeights.resize(sight.across.size());
      for (size_t a = 0; a < sight.across.size(); ++a)
        sight.acrossWeights[a] = Vec3f(sight.across[a].weight * share);
    } else {
      makeFilteredPieces(sight, frontStripes, rearStripes, front, rear, column(0),
                         column(1) - column(0));
      for (Vec3f& w : sight.acrossWeights) w = w * share;
    }
    const auto row = [&](double t) {
      const double rearY = point.y + ((0.5 - t) * frontHeight - point.y) * stretch;
      return (0.5 * rear.heightMm() - rearY) / rear.pitchMm;
    };
    piecesAlongAxis(height_, frontRows_, rearRows_, row(0), row(1) - row(0), 0, -1, sight.down,
                    sight.downStart);
    // The views are at the front layer's resolution: every piece of output pixel (i, j) lies
    // in front pixel (i, j), which the row operators' split P_j = front_j .* m_j relies on.
    for (int i = 0; i < width_; ++i)
      for (uint32_t a = sight.acrossStart[size_t(i)]; a < sight.acrossStart[size_t(i) + 1]; ++a)
        if (sight.across[a].front != i)
          throw std::logic_error("SeenLayers: a piece leaves its column");
    for (int j = 0; j < height_; ++j)
      for (uint32_t k = sight.downStart[size_t(j)]; k < sight.downStart[size_t(j) + 1]; ++k)
        if (sight.down[k].front != j) throw std::logic_error("SeenLayers: a piece leaves its row");
    makeAcrossRuns(sight);
    const int s = int(sights_.size()) - 1;
    for (int j = 0; j < height_; ++j)
      for (uint32_t k = sight.downStart[size_t(j)]; k < sight.downStart[size_t(j) + 1]; ++k)
        if (sight.down[k].rear >= 0)
          rearRowSources_[size_t(sight.down[k].rear)].push_back({j, sight.down[k].weight, s});
  }

  // B: boxFilterX(view, period) (image/box_row.h).
  box_ = BoxRow(width_, design.screenPeriodMm / (frontWidth / double(width_)));
}

// The pieces across between the layers' stripes (one cell a stripe, as the simulator's striped
// layers), merged per rear pixel: a piece whose front and rear stripes pass channel c adds its
// share, times the stripes per pixel of both layers, to channel c of its rear pixel's weight.
// Pieces that pass no channel are dropped.
void SeenLayers::makeFilteredPieces(Sight& sight, int frontStripes, int rearStripes,
                                    const Panel& front, const Panel& rear, double u0,
                                    double du) const {
  std::vector<Piece> cells;
  std::vector<uint32_t> cellStart;
  piecesAlongAxis(width_, frontStripes * frontColumns_, rearStripes * rearColumns_,
                  u0 * rearStripes, du * rearStripes, 0, -1, cells, cellStart);
  const float unfiltered = float(frontStripes * rearStripes);
  std::vector<Piece>& across = sight.across;
  std::vector<Vec3f>& weights = sight.acrossWeights;
  across.clear();
  weights.clear();
  sight.acrossStart.assign(size_t(width_) + 1, 0);
  for (int i = 0; i < width_; ++i) {
    const uint32_t first = uint32_t(across.size());
    sight.acrossStart[size_t(i)] = first;
    for (uint32_t k = cellStart[size_t(i)]; k < cellStart[size_t(i) + 1]; ++k) {
      const Piece& cell = cells[k];
      if (cell.front / frontStripes != i)
        throw std::logic_error("SeenLayers: a piece leaves its column");
      Vec3f pass(1.0f);
      if (frontStripes == 3) pass = pass * stripePasses(front.subpixels, cell.front % 3);
      if (rearStripes == 3 && cell.rear >= 0)
        pass = pass * stripePasses(rear.subpixels, cell.rear % 3);
      if (pass == Vec3f(0.0f)) continue;
      const int rearPixel = cell.rear < 0 ? -1 : cell.rear / rearStripes;
      const Vec3f weight = pass * (cell.weight * unfiltered);
      if (across.size() > first && across.back().rear == rearPixel) {
        across.back().weight += cell.weight;
        weights.back() += weight;
      } else {
        across.push_back({i, rearPixel, cell.weight});
        weights.push_back(weight);
      }
    }
  }
  sight.acrossStart[size_t(width_)] = uint32_t(across.size());
}

void SeenLayers::makeAcrossRuns(Sight& sight) const {
  sight.acrossFirst.assign(3 * size_t(width_), 0.0f);
  sight.acrossSecond.assign(3 * size_t(width_), 0.0f);
  for (int i = 0; i < width_; ++i) {
    const uint32_t begin = sight.acrossStart[size_t(i)];
    const uint32_t count = sight.acrossStart[size_t(i) + 1] - begin;
    const Piece* pieces = &sight.across[begin];
    // Two cells read, so the second must lie inside the rear layer even when its weight is 0.
    const bool even = (count == 1 || count == 2) && pieces[0].rear >= 0 &&
                      pieces[0].rear + 1 < rearColumns_ &&
                      (count == 1 || pieces[1].rear == pieces[0].rear + 1);
    if (rearStripeCells_) {
      // Consecutive cells, every term's read inside the row (kStripeTerms cells from the
      // first).
      bool consecutive = count >= 1 && count <= uint32_t(kStripeTerms) && pieces[0].rear >= 0 &&
                         pieces[0].rear + kStripeTerms <= rearColumns_;
      for (uint32_t m = 1; consecutive && m < count; ++m)
        consecutive = pieces[m].rear == pieces[0].rear + int(m);
      if (!consecutive) {
        sight.unevenColumns.push_back(i);
        continue;
      }
      sight.stripeWeights.resize(size_t(kStripeTerms) * 3 * size_t(width_), 0.0f);
      for (uint32_t m = 0; m < count; ++m)
        for (int c = 0; c < 3; ++c)
          sight.stripeWeights[(m * size_t(width_) + size_t(i)) * 3 + size_t(c)] =
              sight.acrossWeights[begin + m][c];
      const int shift = pieces[0].rear - 3 * i;
      std::vector<AcrossRun>& runs = sight.stripeRuns;
      if (!runs.empty() && runs.back().end == i && runs.back().shift == shift)
        ++runs.back().end;
      else
        runs.push_back({i, i + 1, shift});
      continue;
    }
    if (!even) {
      sight.unevenColumns.push_back(i);
      continue;
    }
    const int shift = pieces[0].rear - i;
    const Vec3f* weights = &sight.acrossWeights[begin];
    for (int c = 0; c < 3; ++c) {
      sight.acrossFirst[3 * size_t(i) + size_t(c)] = weights[0][c];
      sight.acrossSecond[3 * size_t(i) + size_t(c)] = count == 2 ? weights[1][c] : 0.0f;
    }
    std::vector<AcrossRun>& runs = sight.acrossRuns;
    if (!runs.empty() && runs.back().end == i && runs.back().shift == shift)
      ++runs.back().end;
    else
      runs.push_back({i, i + 1, shift});
  }
}

namespace {

// A run of columns (SeenLayers::AcrossRun) over n floats: out[k] = first[k] cells[k] +
// second[k] cells[k + 3] (cells from the run's first rear cell).
PARALLAX_LANE_KERNEL
void gatherRun(const float* cells, const float* first, const float* second, float* out, size_t n) {
  PARALLAX_SIMD
  for (size_t k = 0; k < n; ++k) out[k] = first[k] * cells[k] + second[k] * cells[k + 3];
}

// Its transpose, scaled: cells[k] += scale[k] first[k], then cells[k + 3] += scale[k]
// second[k], with scale[k] = weight filtered[k] front[k] (two loops: the second adds to cells
// the first wrote).
PARALLAX_LANE_KERNEL
void scatterRun(const float* filtered, const float* front, float weight, const float* first,
                const float* second, float* cells, size_t n) {
  PARALLAX_SIMD
  for (size_t k = 0; k < n; ++k) cells[k] += filtered[k] * weight * front[k] * first[k];
  PARALLAX_SIMD
  for (size_t k = 0; k < n; ++k) cells[k + 3] += filtered[k] * weight * front[k] * second[k];
}

}  // namespace

// Plane q of a row of stripe cells (cells 3i' + q) starts at planes[q * planeCells].
void SeenLayers::gatherStripeRuns(const Sight& sight, const Vec3f* cells, Vec3f* out,
                                  std::vector<Vec3f>& planes) const {
  const size_t planeCells = size_t(rearColumns_ / 3);
  planes.resize(3 * planeCells);
  for (size_t i = 0; i < planeCells; ++i)
    for (size_t q = 0; q < 3; ++q) planes[q * planeCells + i] = cells[3 * i + q];
  for (const AcrossRun& run : sight.stripeRuns) {
    const size_t n = 3 * size_t(run.end - run.begin);
    float* into = &out[run.begin].x;
    for (int m = 0; m < kStripeTerms; ++m) {
      // Cell 3i + s + m is plane q = (s + m) mod 3's cell i + (s + m - q) / 3 (s may be
      // negative; the run's first cell is inside the row).
      const int q = ((run.shift + m) % 3 + 3) % 3;
      const Vec3f* plane =
          &planes[size_t(q) * planeCells + size_t(run.begin + (run.shift + m - q) / 3)];
      const float* weights =
          &sight.stripeWeights[(size_t(m) * size_t(width_) + size_t(run.begin)) * 3];
      if (m == 0)
        multiplyLanes(weights, &plane->x, into, n);
      else
        addProductsLanes(weights, &plane->x, into, n);
    }
  }
}

void SeenLayers::scatterStripeRuns(const Sight& sight, const Vec3f* filtered, const Vec3f* frontRow,
                                   float weight, Vec3f* cells) const {
  for (const AcrossRun& run : sight.stripeRuns)
    for (int i = run.begin; i < run.end; ++i) {
      const Vec3f v = filtered[i] * weight * frontRow[i];
      Vec3f* into = cells + 3 * i + run.shift;
      for (int m = 0; m < kStripeTerms; ++m) {
        const float* w = &sight.stripeWeights[(size_t(m) * size_t(width_) + size_t(i)) * 3];
        into[m] += v * Vec3f(w[0], w[1], w[2]);
      }
    }
}

Image SeenLayers::box(const Image& view, int threads) const {
  if (!periodBox_) return view;
  Image out(view.width(), view.height());
  forEachRow(view.height(), threads, [&](int y) { box_.apply(&view.at(0, y), &out.at(0, y)); });
  return out;
}

Image SeenLayers::boxTransposed(const Image& view, int threads) const {
  if (!periodBox_) return view;
  Image out(view.width(), view.height());
  forEachRow(view.height(), threads,
             [&](int y) { box_.applyTransposed(&view.at(0, y), &out.at(0, y)); });
  return out;
}

void SeenLayers::seenRearRow(const LayerRows& rear, int j, Vec3f* seenRear,
                             RowScratch& scratch) const {
  sightRearRow(sights_[0], 0, rear, j, seenRear, scratch);
  if (sights_.size() == 1) return;
  // A pupil: the sights' m_j added up (their weights carry the 1/N of the average).
  scratch.sightRow.resize(size_t(width_));
  for (size_t s = 1; s < sights_.size(); ++s) {
    sightRearRow(sights_[s], int(s), rear, j, scratch.sightRow.data(), scratch);
    addScaledLanes(&scratch.sightRow[0].x, 1.0f, &seenRear[0].x, 3 * size_t(width_));
  }
}

void SeenLayers::sightRearRow(const Sight& sight, int s, const LayerRows& rear, int j,
                              Vec3f* seenRear, RowScratch& scratch) const {
  // m_j[i] = sum_k w_k sum_a w_a rear[r_k][c_a] = sum_a w_a (sum_k w_k rear[r_k])[c_a]: the
  // vertical blend once per row (a vectorised loop), then one pass of the pieces along it.
  const Piece* pieces = sight.down.data() + sight.downStart[size_t(j)];
  const size_t pieceCount = sight.downStart[size_t(j) + 1] - sight.downStart[size_t(j)];
  RowScratch::Blend* kept = nullptr;
  if (scratch.keepBlends) {
    for (RowScratch::Blend& b : scratch.blends)
      if (b.rearFirst == rear.first && b.sight == s) kept = &b;
    if (!kept) kept = &scratch.blends.emplace_back(RowScratch::Blend{rear.first, s, {}, {}, false});
  }
  const auto sameRows = [&] {
    if (kept->pieces.size() != pieceCount || kept->rows.size() != size_t(rearColumns_))
      return false;
    for (size_t k = 0; k < pieceCount; ++k)
      if (kept->pieces[k].rear != pieces[k].rear || kept->pieces[k].weight != pieces[k].weight)
        return false;
    return true;
  };
  std::vector<Vec3f>& blend = kept ? kept->rows : scratch.rearRow;
  bool any = false;
  if (kept && sameRows()) {
    any = kept->any;
  } else {
    blend.assign(size_t(rearColumns_), Vec3f(0.0f));
    for (size_t k = 0; k < pieceCount; ++k) {
      const Piece& vertical = pieces[k];
      if (vertical.rear < 0) continue;
      any = true;
      addScaledLanes(&rear.row(vertical.rear)->x, vertical.weight, &blend[0].x,
                     3 * size_t(rearColumns_));
    }
    if (kept) kept->pieces.assign(pieces, pieces + pieceCount), kept->any = any;
  }
  if (!any) {
    std::fill(seenRear, seenRear + width_, Vec3f(0.0f));
    return;
  }
  for (const AcrossRun& run : sight.acrossRuns) {
    const size_t first = 3 * size_t(run.begin);
    gatherRun(&blend[size_t(run.begin + run.shift)].x, &sight.acrossFirst[first],
              &sight.acrossSecond[first], &seenRear[run.begin].x, 3 * size_t(run.end - run.begin));
  }
  if (!sight.stripeRuns.empty()) gatherStripeRuns(sight, blend.data(), seenRear, scratch.planes);
  for (const int i : sight.unevenColumns) {
    Vec3f light(0.0f);
    for (uint32_t a = sight.acrossStart[size_t(i)]; a < sight.acrossStart[size_t(i) + 1]; ++a) {
      const Piece& p = sight.across[a];
      if (p.rear >= 0) light += blend[size_t(p.rear)] * sight.acrossWeights[a];
    }
    seenRear[i] = light;
  }
}

void SeenLayers::viewRowSeen(const Vec3f* frontRow, const Vec3f* seenRear, Vec3f* out,
                             RowScratch& scratch) const {
  Vec3f* product =
      periodBox_ ? (scratch.product.resize(size_t(width_)), scratch.product.data()) : out;
  multiplyLanes(&frontRow[0].x, &seenRear[0].x, &product[0].x, 3 * size_t(width_));
  if (periodBox_) box_.apply(product, out);
}

void SeenLayers::viewRowSeen(const Vec3f* frontRow, const float* greySeenRear, Vec3f* out,
                             RowScratch& scratch) const {
  Vec3f* product =
      periodBox_ ? (scratch.product.resize(size_t(width_)), scratch.product.data()) : out;
  multiplyByGreyLanes(&frontRow[0].x, greySeenRear, &product[0].x, size_t(width_));
  if (periodBox_) box_.apply(product, out);
}

// B^T residual (or the residual itself without the box), in scratch.filtered.
const Vec3f* SeenLayers::boxTransposedInScratch(const Vec3f* residual, RowScratch& scratch) const {
  if (!periodBox_) return residual;
  scratch.filtered.resize(size_t(width_));
  box_.applyTransposed(residual, scratch.filtered.data());
  return scratch.filtered.data();
}

void SeenLayers::addFrontGradientRowSeen(const Vec3f* residual, const Vec3f* seenRear,
                                         Vec3f* gradRow, RowScratch& scratch) const {
  const Vec3f* r = boxTransposedInScratch(residual, scratch);
  addProductsLanes(&r[0].x, &seenRear[0].x, &gradRow[0].x, 3 * size_t(width_));
}

void SeenLayers::addFrontGradientRowSeen(const Vec3f* residual, const float* greySeenRear,
                                         Vec3f* gradRow, RowScratch& scratch) const {
  const Vec3f* r = boxTransposedInScratch(residual, scratch);
  addProductsByGreyLanes(&r[0].x, greySeenRear, &gradRow[0].x, size_t(width_));
}

void SeenLayers::viewRow(const LayerRows& front, const LayerRows& rear, int j, Vec3f* out,
                         RowScratch& scratch) const {
  scratch.seenRear.resize(size_t(width_));
  seenRearRow(rear, j, scratch.seenRear.data(), scratch);
  viewRowSeen(front.row(j), scratch.seenRear.data(), out, scratch);
}

void SeenLayers::addFrontGradientRow(const Vec3f* residual, const Image& rear, int j,
                                     Image& gradFront, RowScratch& scratch) const {
  scratch.seenRear.resize(size_t(width_));
  seenRearRow(rear, j, scratch.seenRear.data(), scratch);
  addFrontGradientRowSeen(residual, scratch.seenRear.data(), &gradFront.at(0, j), scratch);
}

Image SeenLayers::view(const LayerRows& front, const LayerRows& rear, int threads) const {
  checkLayer(front, frontColumns_, frontRows_, "front");
  checkLayer(rear, rearColumns_, rearRows_, "rear");
  Image out(width_, height_);
  forEachRow(height_, threads, [&](int j) {
    RowScratch scratch;
    viewRow(front, rear, j, &out.at(0, j), scratch);
  });
  return out;
}

void SeenLayers::addFrontGradient(const Image& residual, const Image& rear, Image& gradFront,
                                  int threads) const {
  checkLayer(rear, rearColumns_, rearRows_, "rear");
  checkLayer(gradFront, frontColumns_, frontRows_, "front");
  // Output row j's pieces all lie in front row j: rows in parallel write disjoint rows.
  forEachRow(height_, threads, [&](int j) {
    RowScratch scratch;
    addFrontGradientRow(&residual.at(0, j), rear, j, gradFront, scratch);
  });
}

void SeenLayers::addRearGradient(const Image& residual, const Image& front, Image& gradRear,
                                 int threads) const {
  checkLayer(front, frontColumns_, frontRows_, "front");
  checkLayer(gradRear, rearColumns_, rearRows_, "rear");
  const Image r = boxTransposed(residual, threads);
  // Each rear row gathers from the output rows that meet it, in row order.
  forEachRow(rearRows_, threads, [&](int rearRow) {
    for (const RearSource& source : rearRowSources_[size_t(rearRow)])
      addRearGradientFromRow(&r.at(0, source.outputRow), front, source.outputRow, source.weight,
                             &gradRear.at(0, rearRow), source.sight);
  });
}

void SeenLayers::boxTransposedRowInto(const Vec3f* residual, Vec3f* filtered) const {
  if (periodBox_)
    box_.applyTransposed(residual, filtered);
  else
    std::copy(residual, residual + width_, filtered);
}

void SeenLayers::addRearGradientFromRow(const Vec3f* filtered, const Image& front, int j,
                                        float weight, Vec3f* gradRearRow, int s) const {
  const Sight& sight = sights_[size_t(s)];
  const Vec3f* frontRow = &front.at(0, j);  // output row j lies in front row j
  for (const AcrossRun& run : sight.acrossRuns) {
    const size_t first = 3 * size_t(run.begin);
    scatterRun(&filtered[run.begin].x, &frontRow[run.begin].x, weight, &sight.acrossFirst[first],
               &sight.acrossSecond[first], &gradRearRow[run.begin + run.shift].x,
               3 * size_t(run.end - run.begin));
  }
  scatterStripeRuns(sight, filtered, frontRow, weight, gradRearRow);
  for (const int i : sight.unevenColumns) {
    const Vec3f v = filtered[i] * weight;
    for (uint32_t a = sight.acrossStart[size_t(i)]; a < sight.acrossStart[size_t(i) + 1]; ++a) {
      const Piece& p = sight.across[a];
      if (p.rear < 0) continue;
      gradRearRow[p.rear] += v * frontRow[p.front] * sight.acrossWeights[a];
    }
  }
}

}  // namespace parallax
