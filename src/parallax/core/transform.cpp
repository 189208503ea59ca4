#include "parallax/core/transform.h"

#include <cmath>
#include <stdexcept>

namespace parallax {

Mat4 Mat4::identity() {
  Mat4 r;
  for (int i = 0; i < 4; ++i) r.m[i][i] = 1.0f;
  return r;
}

Mat4 Mat4::operator*(const Mat4& o) const {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += double(m[i][k]) * o.m[k][j];
      r.m[i][j] = float(s);
    }
  return r;
}

// Gauss-Jordan elimination with partial pivoting, in double precision.
bool invert(const Mat4& a, Mat4& inverse) {
  double w[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      w[i][j] = a.m[i][j];
      w[i][j + 4] = (i == j) ? 1.0 : 0.0;
    }
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 4; ++r)
      if (std::abs(w[r][col]) > std::abs(w[pivot][col])) pivot = r;
    if (std::abs(w[pivot][col]) < 1e-12) return false;
    if (pivot != col)
      for (int j = 0; j < 8; ++j) std::swap(w[col][j], w[pivot][j]);
    const double d = w[col][col];
    for (int j = 0; j < 8; ++j) w[col][j] /= d;
    for (int r = 0; r < 4; ++r) {
      if (r == col) continue;
      const double f = w[r][col];
      for (int j = 0; j < 8; ++j) w[r][j] -= f * w[col][j];
    }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) inverse.m[i][j] = float(w[i][j + 4]);
  return true;
}

Transform::Transform(const Mat4& matrix) : matrix_(matrix) {
  if (!invert(matrix, inverse_)) throw std::invalid_argument("singular transform matrix");
}

Transform Transform::translate(const Vec3f& t) {
  Mat4 m = Mat4::identity(), inv = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    m.m[i][3] = t[i];
    inv.m[i][3] = -t[i];
  }
  return {m, inv};
}

Transform Transform::scale(const Vec3f& s) {
  if (s.x == 0 || s.y == 0 || s.z == 0) throw std::invalid_argument("zero scale");
  Mat4 m = Mat4::identity(), inv = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    m.m[i][i] = s[i];
    inv.m[i][i] = 1.0f / s[i];
  }
  return {m, inv};
}

// Rodrigues' rotation formula; the inverse of a rotation is its transpose.
Transform Transform::rotate(float degrees, const Vec3f& axis) {
  const double len = std::sqrt(double(dot(axis, axis)));
  if (len == 0) throw std::invalid_argument("zero rotation axis");
  const double x = axis.x / len, y = axis.y / len, z = axis.z / len;
  const double th = double(degrees) * 3.14159265358979323846 / 180.0;
  const double c = std::cos(th), s = std::sin(th), t = 1 - c;
  Mat4 m = Mat4::identity();
  const double r[3][3] = {{t * x * x + c, t * x * y - s * z, t * x * z + s * y},
                          {t * x * y + s * z, t * y * y + c, t * y * z - s * x},
                          {t * x * z - s * y, t * y * z + s * x, t * z * z + c}};
  Mat4 inv = Mat4::identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      m.m[i][j] = float(r[i][j]);
      inv.m[j][i] = float(r[i][j]);
    }
  return {m, inv};
}

Transform Transform::lookAt(const Vec3f& eye, const Vec3f& target, const Vec3f& up) {
  const Vec3f back = normalize(eye - target);  // camera +z
  const Vec3f right = normalize(cross(up, back));
  const Vec3f trueUp = cross(back, right);
  Mat4 worldFromCamera = Mat4::identity();
  for (int i = 0; i < 3; ++i) {
    worldFromCamera.m[i][0] = right[i];
    worldFromCamera.m[i][1] = trueUp[i];
    worldFromCamera.m[i][2] = back[i];
    worldFromCamera.m[i][3] = eye[i];
  }
  return Transform(worldFromCamera).inverse();
}

Vec3f Transform::point(const Vec3f& p) const {
  const auto& a = matrix_.m;
  Vec3f r;
  for (int i = 0; i < 3; ++i) r[i] = a[i][0] * p.x + a[i][1] * p.y + a[i][2] * p.z + a[i][3];
  const float w = a[3][0] * p.x + a[3][1] * p.y + a[3][2] * p.z + a[3][3];
  return w == 1.0f ? r : r / w;
}

Vec3f Transform::vector(const Vec3f& v) const {
  const auto& a = matrix_.m;
  Vec3f r;
  for (int i = 0; i < 3; ++i) r[i] = a[i][0] * v.x + a[i][1] * v.y + a[i][2] * v.z;
  return r;
}

Vec3f Transform::normal(const Vec3f& n) const {
  const auto& b = inverse_.m;
  Vec3f r;
  for (int i = 0; i < 3; ++i) r[i] = b[0][i] * n.x + b[1][i] * n.y + b[2][i] * n.z;
  return r;
}

bool Transform::swapsHandedness() const {
  const auto& a = matrix_.m;
  const double det = a[0][0] * (double(a[1][1]) * a[2][2] - double(a[1][2]) * a[2][1]) -
                     a[0][1] * (double(a[1][0]) * a[2][2] - double(a[1][2]) * a[2][0]) +
                     a[0][2] * (double(a[1][0]) * a[2][1] - double(a[1][1]) * a[2][0]);
  return det < 0;
}

}  // namespace parallax
