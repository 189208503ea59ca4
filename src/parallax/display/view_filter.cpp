#include "parallax/display/view_filter.h"

#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <cmath>

namespace parallax {

bool parseViewFilterKind(const std::string& text, ViewFilterKind& kind) {
  for (ViewFilterKind k : {ViewFilterKind::None, ViewFilterKind::View, ViewFilterKind::Tent,
                           ViewFilterKind::Gaussian, ViewFilterKind::Period})
    if (text == viewFilterName(k)) {
      kind = k;
      return true;
    }
  return false;
}

const char* viewFilterName(ViewFilterKind kind) {
  switch (kind) {
    case ViewFilterKind::None:
      return "none";
    case ViewFilterKind::View:
      return "view";
    case ViewFilterKind::Tent:
      return "tent";
    case ViewFilterKind::Gaussian:
      return "gaussian";
    case ViewFilterKind::Period:
      return "period";
  }
  return "?";
}

namespace {

// Gaussian full width at half maximum over sigma: 2 sqrt(2 ln 2).
constexpr double kFwhmOverSigma = 2.3548200450309493;
constexpr double kGaussianCut = 2.0;  // in sigma

// The filter's cumulative distribution at offset x (views), for a width w.
double cdf(ViewFilterKind kind, double w, double x) {
  switch (kind) {
    case ViewFilterKind::View:  // box on [-w/2, w/2]
      return std::clamp(x / w + 0.5, 0.0, 1.0);
    case ViewFilterKind::Tent: {  // triangle on [-w, w]
      const double t = std::clamp(x / w, -1.0, 1.0);
      return t < 0 ? 0.5 * (1 + t) * (1 + t) : 1 - 0.5 * (1 - t) * (1 - t);
    }
    case ViewFilterKind::Gaussian: {  // truncated at +-2 sigma, renormalised
      const double sigma = w / kFwhmOverSigma;
      const double t = std::clamp(x / sigma, -kGaussianCut, kGaussianCut);
      const double edge = std::erf(kGaussianCut / std::sqrt(2.0));
      return 0.5 * (1 + std::erf(t / std::sqrt(2.0)) / edge);
    }
    default:
      return x < 0 ? 0.0 : 1.0;
  }
}

}  // namespace

ViewFilterWarp::ViewFilterWarp(const ViewFilter& filter) : kind_(filter.kind) {
  const double w = filter.widthViews;
  switch (filter.kind) {
    case ViewFilterKind::View:
      halfSupport_ = 0.5 * w;
      break;
    case ViewFilterKind::Tent:
      halfSupport_ = w;
      break;
    case ViewFilterKind::Gaussian:
      halfSupport_ = kGaussianCut * w / kFwhmOverSigma;
      break;
    default:
      halfSupport_ = 0;
      break;
  }
  // The inverse CDF at kTable + 1 evenly spaced probabilities, by bisection on the CDF.
  for (int i = 0; i <= kTable; ++i) {
    const double p = double(i) / kTable;
    double lo = -halfSupport_, hi = halfSupport_;
    for (int step = 0; step < 60 && halfSupport_ > 0; ++step) {
      const double mid = 0.5 * (lo + hi);
      (cdf(filter.kind, w, mid) < p ? lo : hi) = mid;
    }
    inverseCdf_[size_t(i)] = 0.5 * (lo + hi);
  }
}

PARALLAX_LANE_KERNEL double ViewFilterWarp::operator()(double u) const {
  u = std::clamp(u, 0.0, 1.0);
  // Closed forms where there are (the box's and the triangle's inverse CDFs), the table else.
  if (kind_ == ViewFilterKind::View) return (u - 0.5) * 2 * halfSupport_;
  if (kind_ == ViewFilterKind::Tent)
    return halfSupport_ * (u < 0.5 ? std::sqrt(2 * u) - 1 : 1 - std::sqrt(2 * (1 - u)));
  const double x = u * kTable;
  const int i = std::min(int(x), kTable - 1);
  const double f = x - i;
  return inverseCdf_[size_t(i)] * (1 - f) + inverseCdf_[size_t(i) + 1] * f;
}

}  // namespace parallax
