#include "parallax/sim/seen_layers.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "parallax/core/parallel.h"

namespace parallax {

namespace {

template <class Body>
void forEachRow(int rows, int threads, const Body& body) {
  parallelFor(rows, threads, 8, [&](int64_t begin, int64_t end) {
    for (int64_t row = begin; row != end; ++row) body(int(row));
  });
}

void checkLayer(const Image& layer, int columns, int rows, const char* what) {
  if (layer.width() != columns || layer.height() != rows)
    throw std::invalid_argument(std::string("SeenLayers: the ") + what +
                                " layer's size differs from its panel");
}

}  // namespace

SeenLayers::SeenLayers(const DisplayDesign& design, const Vec3d& eye, bool periodBox)
    : design_(design), eye_(eye), periodBox_(periodBox) {
  const DisplaySpec& spec = design.spec;
  imageInFront_ = spec.order == LayerOrder::BarrierBack;
  const Panel& front = imageInFront_ ? spec.imagePanel : spec.maskPanel;
  const Panel& rear = imageInFront_ ? spec.maskPanel : spec.imagePanel;
  frontColumns_ = width_ = front.width;
  frontRows_ = height_ = front.height;
  rearColumns_ = rear.width;
  rearRows_ = rear.height;
  // The simulator's geometry (DisplaySimulator::view): x across the front layer is
  // (t - 1/2) frontWidth, and the eye's line through it meets the rear layer stretched by
  // (e.z + g) / e.z about the eye.
  const double stretch = (eye.z + design.gapMm) / eye.z;
  const double frontWidth = front.widthMm(), frontHeight = front.heightMm();
  const auto column = [&](double t) {
    const double rearX = eye.x + ((t - 0.5) * frontWidth - eye.x) * stretch;
    return (rearX + 0.5 * rear.widthMm()) / rear.pitchMm;
  };
  piecesAlongAxis(width_, frontColumns_, rearColumns_, column(0), column(1) - column(0), 0, -1,
                  across_, acrossStart_);
  const auto row = [&](double t) {
    const double rearY = eye.y + ((0.5 - t) * frontHeight - eye.y) * stretch;
    return (0.5 * rear.heightMm() - rearY) / rear.pitchMm;
  };
  piecesAlongAxis(height_, frontRows_, rearRows_, row(0), row(1) - row(0), 0, -1, down_,
                  downStart_);
  // The views are at the front layer's resolution: every piece of output pixel (i, j) lies in
  // front pixel (i, j), which the row operators' split P_j = front_j .* m_j relies on.
  for (int i = 0; i < width_; ++i)
    for (uint32_t a = acrossStart_[size_t(i)]; a < acrossStart_[size_t(i) + 1]; ++a)
      if (across_[a].front != i) throw std::logic_error("SeenLayers: a piece leaves its column");
  for (int j = 0; j < height_; ++j)
    for (uint32_t k = downStart_[size_t(j)]; k < downStart_[size_t(j) + 1]; ++k)
      if (down_[k].front != j) throw std::logic_error("SeenLayers: a piece leaves its row");
  rearRowSources_.assign(size_t(rearRows_), {});
  for (int j = 0; j < height_; ++j)
    for (uint32_t k = downStart_[size_t(j)]; k < downStart_[size_t(j) + 1]; ++k)
      if (down_[k].rear >= 0)
        rearRowSources_[size_t(down_[k].rear)].push_back({j, down_[k].weight});

  // B: boxFilterX(view, period): output column x reads its window [x + 1/2 - w/2,
  // x + 1/2 + w/2] clipped to the row; B^T reads the same window around each column, where
  // clipping it to the row stands for the zero row outside.
  const double w = design.screenPeriodMm / (frontWidth / double(width_));
  const auto end = [this](double t) {
    t = std::clamp(t, 0.0, double(width_));
    const int index = std::min(int(std::floor(t)), width_ - 1);
    return BoxEnd{index, t - index};
  };
  for (int x = 0; x < width_; ++x) {
    const double lo = std::max(0.0, x + 0.5 - 0.5 * w),
                 hi = std::min(double(width_), x + 0.5 + 0.5 * w);
    boxLo_.push_back(end(lo));
    boxHi_.push_back(end(hi));
    boxInverseLength_.push_back(1.0 / (hi - lo));
    unclippedLo_.push_back(end(x + 0.5 - 0.5 * w));
    unclippedHi_.push_back(end(x + 0.5 + 0.5 * w));
  }
}

// B as boxFilterX computes it: output x is the integral of the box-pixel row over
// [lo_x, hi_x] = [x + 1/2 - w/2, x + 1/2 + w/2] clipped to the row, over its length, read off a
// prefix sum. Its transpose: pixel k receives sum_x y_x / |[lo_x, hi_x]| times the overlap of
// [k, k+1] with the unclipped window (the row clips nothing inside [k, k+1]), which is the
// integral of the box-pixel row h_x = y_x / |[lo_x, hi_x]| over the window centred on k: the
// same prefix-sum reading without the division. The three channels run together (one pass).
namespace {

// The integral over [0, t] of the box-pixel row whose prefix sums are `prefix` and whose
// pixels are `at(index)`, at a window's end t = index + fraction.
template <class Pixel>
Vec3d integralTo(const std::vector<Vec3d>& prefix, const Pixel& pixel, int index, double fraction) {
  const Vec3d& p = prefix[size_t(index)];
  return {p.x + fraction * pixel.x, p.y + fraction * pixel.y, p.z + fraction * pixel.z};
}

}  // namespace

void SeenLayers::boxRow(const Vec3f* row, Vec3f* out, std::vector<Vec3d>& prefix) const {
  prefix.resize(size_t(width_) + 1);
  prefix[0] = {};
  for (int x = 0; x < width_; ++x) {
    const Vec3d& p = prefix[size_t(x)];
    prefix[size_t(x) + 1] = {p.x + row[x].x, p.y + row[x].y, p.z + row[x].z};
  }
  for (int x = 0; x < width_; ++x) {
    const BoxEnd &lo = boxLo_[size_t(x)], &hi = boxHi_[size_t(x)];
    const Vec3d a = integralTo(prefix, row[hi.index], hi.index, hi.fraction);
    const Vec3d b = integralTo(prefix, row[lo.index], lo.index, lo.fraction);
    const double inv = boxInverseLength_[size_t(x)];
    out[x] = Vec3f(float((a.x - b.x) * inv), float((a.y - b.y) * inv), float((a.z - b.z) * inv));
  }
}

void SeenLayers::boxTransposedRow(const Vec3f* row, Vec3f* out, std::vector<Vec3d>& h,
                                  std::vector<Vec3d>& prefix) const {
  h.resize(size_t(width_));
  prefix.resize(size_t(width_) + 1);
  prefix[0] = {};
  for (int x = 0; x < width_; ++x) {
    const double inv = boxInverseLength_[size_t(x)];
    h[size_t(x)] = {row[x].x * inv, row[x].y * inv, row[x].z * inv};
    const Vec3d &p = prefix[size_t(x)], &v = h[size_t(x)];
    prefix[size_t(x) + 1] = {p.x + v.x, p.y + v.y, p.z + v.z};
  }
  // The integral of h over [0, t] (h = 0 outside the row: t is clamped to it).
  for (int k = 0; k < width_; ++k) {
    const BoxEnd &lo = unclippedLo_[size_t(k)], &hi = unclippedHi_[size_t(k)];
    const Vec3d a = integralTo(prefix, h[size_t(hi.index)], hi.index, hi.fraction);
    const Vec3d b = integralTo(prefix, h[size_t(lo.index)], lo.index, lo.fraction);
    out[k] = Vec3f(float(a.x - b.x), float(a.y - b.y), float(a.z - b.z));
  }
}

Image SeenLayers::box(const Image& view, int threads) const {
  if (!periodBox_) return view;
  Image out(view.width(), view.height());
  forEachRow(view.height(), threads, [&](int y) {
    std::vector<Vec3d> prefix;
    boxRow(&view.at(0, y), &out.at(0, y), prefix);
  });
  return out;
}

Image SeenLayers::boxTransposed(const Image& view, int threads) const {
  if (!periodBox_) return view;
  Image out(view.width(), view.height());
  forEachRow(view.height(), threads, [&](int y) {
    std::vector<Vec3d> h, prefix;
    boxTransposedRow(&view.at(0, y), &out.at(0, y), h, prefix);
  });
  return out;
}

void SeenLayers::seenRearRow(const Image& rear, int j, Vec3f* seenRear) const {
  std::fill(seenRear, seenRear + width_, Vec3f(0.0f));
  for (uint32_t k = downStart_[size_t(j)]; k < downStart_[size_t(j) + 1]; ++k) {
    const Piece& vertical = down_[k];
    if (vertical.rear < 0) continue;
    const Vec3f* rearRow = &rear.at(0, vertical.rear);
    for (int i = 0; i < width_; ++i) {
      Vec3f light(0.0f);
      for (uint32_t a = acrossStart_[size_t(i)]; a < acrossStart_[size_t(i) + 1]; ++a) {
        const Piece& p = across_[a];
        if (p.rear >= 0) light += rearRow[p.rear] * p.weight;
      }
      seenRear[i] += light * vertical.weight;
    }
  }
}

void SeenLayers::viewRowSeen(const Vec3f* frontRow, const Vec3f* seenRear, Vec3f* out,
                             RowScratch& scratch) const {
  Vec3f* product =
      periodBox_ ? (scratch.product.resize(size_t(width_)), scratch.product.data()) : out;
  for (int i = 0; i < width_; ++i) product[i] = frontRow[i] * seenRear[i];
  if (periodBox_) boxRow(product, out, scratch.prefix);
}

void SeenLayers::addFrontGradientRowSeen(const Vec3f* residual, const Vec3f* seenRear,
                                         Vec3f* gradRow, RowScratch& scratch) const {
  const Vec3f* r = residual;
  if (periodBox_) {
    scratch.filtered.resize(size_t(width_));
    boxTransposedRow(residual, scratch.filtered.data(), scratch.scaled, scratch.prefix);
    r = scratch.filtered.data();
  }
  for (int i = 0; i < width_; ++i) gradRow[i] += r[i] * seenRear[i];
}

void SeenLayers::viewRow(const Image& front, const Image& rear, int j, Vec3f* out,
                         RowScratch& scratch) const {
  scratch.seenRear.resize(size_t(width_));
  seenRearRow(rear, j, scratch.seenRear.data());
  viewRowSeen(&front.at(0, j), scratch.seenRear.data(), out, scratch);
}

void SeenLayers::addFrontGradientRow(const Vec3f* residual, const Image& rear, int j,
                                     Image& gradFront, RowScratch& scratch) const {
  scratch.seenRear.resize(size_t(width_));
  seenRearRow(rear, j, scratch.seenRear.data());
  addFrontGradientRowSeen(residual, scratch.seenRear.data(), &gradFront.at(0, j), scratch);
}

Image SeenLayers::view(const Image& front, const Image& rear, int threads) const {
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
    for (const auto& [j, weight] : rearRowSources_[size_t(rearRow)]) {
      const int frontRow = j;  // output row j lies in front row j
      for (int i = 0; i < width_; ++i) {
        const Vec3f v = r.at(i, j) * weight;
        for (uint32_t a = acrossStart_[size_t(i)]; a < acrossStart_[size_t(i) + 1]; ++a) {
          const Piece& p = across_[a];
          if (p.rear < 0) continue;
          gradRear.at(p.rear, rearRow) += v * front.at(p.front, frontRow) * p.weight;
        }
      }
    }
  });
}

}  // namespace parallax
