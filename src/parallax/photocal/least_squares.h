// Small dense least squares for the estimators: normal equations accumulated row by row and
// solved by Gaussian elimination with partial pivoting (a handful of unknowns, so precision is
// not at stake; the rows are scaled by the caller).
#pragma once

#include <cmath>
#include <vector>

namespace parallax::photocal {

class LeastSquares {
 public:
  explicit LeastSquares(int unknowns)
      : n_(unknowns), normal_(size_t(unknowns * unknowns), 0.0), rhs_(size_t(unknowns), 0.0) {}

  // One equation: sum_i row[i] x_i = value, with weight w (1 / variance).
  void add(const double* row, double value, double weight = 1.0) {
    for (int i = 0; i < n_; ++i) {
      rhs_[size_t(i)] += weight * row[i] * value;
      for (int j = 0; j < n_; ++j) normal_[size_t(i * n_ + j)] += weight * row[i] * row[j];
    }
    ++rows_;
  }
  int rows() const { return rows_; }

  // The solution, and the inverse of the normal matrix (the unknowns' covariance up to the
  // residual variance) in `covariance` when given. Returns false for a singular system.
  bool solve(std::vector<double>& x, std::vector<double>* covariance = nullptr) const {
    const int n = n_, m = 2 * n_ + 1;
    std::vector<double> a(size_t(n * m), 0.0);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) a[size_t(i * m + j)] = normal_[size_t(i * n + j)];
      a[size_t(i * m + n + i)] = 1.0;
      a[size_t(i * m + 2 * n)] = rhs_[size_t(i)];
    }
    for (int c = 0; c < n; ++c) {
      int pivot = c;
      for (int r = c + 1; r < n; ++r)
        if (std::abs(a[size_t(r * m + c)]) > std::abs(a[size_t(pivot * m + c)])) pivot = r;
      if (!(std::abs(a[size_t(pivot * m + c)]) > 1e-300)) return false;
      if (pivot != c)
        for (int j = 0; j < m; ++j) std::swap(a[size_t(c * m + j)], a[size_t(pivot * m + j)]);
      const double d = a[size_t(c * m + c)];
      for (int j = 0; j < m; ++j) a[size_t(c * m + j)] /= d;
      for (int r = 0; r < n; ++r) {
        if (r == c) continue;
        const double f = a[size_t(r * m + c)];
        if (f != 0.0)
          for (int j = 0; j < m; ++j) a[size_t(r * m + j)] -= f * a[size_t(c * m + j)];
      }
    }
    x.assign(size_t(n), 0.0);
    for (int i = 0; i < n; ++i) x[size_t(i)] = a[size_t(i * m + 2 * n)];
    if (covariance) {
      covariance->assign(size_t(n * n), 0.0);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) (*covariance)[size_t(i * n + j)] = a[size_t(i * m + n + j)];
    }
    return true;
  }

 private:
  int n_;
  std::vector<double> normal_, rhs_;
  int rows_ = 0;
};

}  // namespace parallax::photocal
