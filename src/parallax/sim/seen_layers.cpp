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
// same prefix-sum reading without the division.
void SeenLayers::boxRow(const Vec3f* row, Vec3f* out, std::vector<double>& prefix) const {
  prefix.assign(size_t(width_) + 1, 0.0);
  for (int c = 0; c < 3; ++c) {
    for (int x = 0; x < width_; ++x) prefix[size_t(x) + 1] = prefix[size_t(x)] + row[x][c];
    // The integral of the box-pixel row over [0, t] at a window's end.
    const auto integral = [&](const BoxEnd& e) {
      return prefix[size_t(e.index)] + e.fraction * row[e.index][c];
    };
    for (int x = 0; x < width_; ++x)
      out[x][c] = float((integral(boxHi_[size_t(x)]) - integral(boxLo_[size_t(x)])) *
                        boxInverseLength_[size_t(x)]);
  }
}

void SeenLayers::boxTransposedRow(const Vec3f* row, Vec3f* out, std::vector<double>& h,
                                  std::vector<double>& prefix) const {
  h.assign(size_t(width_), 0.0);
  prefix.assign(size_t(width_) + 1, 0.0);
  for (int c = 0; c < 3; ++c) {
    for (int x = 0; x < width_; ++x) {
      h[size_t(x)] = row[x][c] * boxInverseLength_[size_t(x)];
      prefix[size_t(x) + 1] = prefix[size_t(x)] + h[size_t(x)];
    }
    // The integral of h over [0, t] (h = 0 outside the row: t is clamped to it).
    const auto integral = [&](const BoxEnd& e) {
      return prefix[size_t(e.index)] + e.fraction * h[size_t(e.index)];
    };
    for (int k = 0; k < width_; ++k)
      out[k][c] = float(integral(unclippedHi_[size_t(k)]) - integral(unclippedLo_[size_t(k)]));
  }
}

Image SeenLayers::box(const Image& view, int threads) const {
  if (!periodBox_) return view;
  Image out(view.width(), view.height());
  forEachRow(view.height(), threads, [&](int y) {
    std::vector<double> prefix;
    boxRow(&view.at(0, y), &out.at(0, y), prefix);
  });
  return out;
}

Image SeenLayers::boxTransposed(const Image& view, int threads) const {
  if (!periodBox_) return view;
  Image out(view.width(), view.height());
  forEachRow(view.height(), threads, [&](int y) {
    std::vector<double> h, prefix;
    boxTransposedRow(&view.at(0, y), &out.at(0, y), h, prefix);
  });
  return out;
}

void SeenLayers::productRow(const Image& front, const Image& rear, int j, Vec3f* product) const {
  std::fill(product, product + width_, Vec3f(0.0f));
  for (uint32_t k = downStart_[size_t(j)]; k < downStart_[size_t(j) + 1]; ++k) {
    const Piece& vertical = down_[k];
    if (vertical.rear < 0) continue;
    for (int i = 0; i < width_; ++i) {
      Vec3f light(0.0f);
      for (uint32_t a = acrossStart_[size_t(i)]; a < acrossStart_[size_t(i) + 1]; ++a) {
        const Piece& p = across_[a];
        if (p.rear < 0) continue;
        light += front.at(p.front, vertical.front) * rear.at(p.rear, vertical.rear) * p.weight;
      }
      product[i] += light * vertical.weight;
    }
  }
}

void SeenLayers::frontAdjointRow(const Vec3f* r, const Image& rear, int j, Image& gradFront) const {
  for (uint32_t k = downStart_[size_t(j)]; k < downStart_[size_t(j) + 1]; ++k) {
    const Piece& vertical = down_[k];
    if (vertical.rear < 0) continue;
    for (int i = 0; i < width_; ++i) {
      const Vec3f v = r[i] * vertical.weight;
      for (uint32_t a = acrossStart_[size_t(i)]; a < acrossStart_[size_t(i) + 1]; ++a) {
        const Piece& p = across_[a];
        if (p.rear < 0) continue;
        gradFront.at(p.front, vertical.front) += v * rear.at(p.rear, vertical.rear) * p.weight;
      }
    }
  }
}

void SeenLayers::viewRow(const Image& front, const Image& rear, int j, Vec3f* out,
                         RowScratch& scratch) const {
  if (!periodBox_) return productRow(front, rear, j, out);
  scratch.product.resize(size_t(width_));
  productRow(front, rear, j, scratch.product.data());
  boxRow(scratch.product.data(), out, scratch.prefix);
}

void SeenLayers::addFrontGradientRow(const Vec3f* residual, const Image& rear, int j,
                                     Image& gradFront, RowScratch& scratch) const {
  if (!periodBox_) return frontAdjointRow(residual, rear, j, gradFront);
  scratch.filtered.resize(size_t(width_));
  boxTransposedRow(residual, scratch.filtered.data(), scratch.scaled, scratch.prefix);
  frontAdjointRow(scratch.filtered.data(), rear, j, gradFront);
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
