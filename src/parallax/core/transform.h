// Affine transforms as 4x4 matrices with their inverse kept alongside (pbrt's convention).
// Name variables by the frames they connect: `worldFromObject.point(p)` takes an object-space
// point into world space.
#pragma once

#include <array>

#include "parallax/core/math.h"

namespace parallax {

struct Mat4 {
  std::array<std::array<float, 4>, 4> m{};  // row-major, m[row][col]

  static Mat4 identity();
  Mat4 operator*(const Mat4& o) const;
  bool operator==(const Mat4&) const = default;
};

// Inverse of a general 4x4 matrix; returns false if it is singular.
bool invert(const Mat4& a, Mat4& inverse);

class Transform {
 public:
  Transform() : matrix_(Mat4::identity()), inverse_(Mat4::identity()) {}
  // Throws std::invalid_argument for a singular matrix.
  explicit Transform(const Mat4& matrix);
  Transform(const Mat4& matrix, const Mat4& inverse) : matrix_(matrix), inverse_(inverse) {}

  static Transform translate(const Vec3f& t);
  static Transform scale(const Vec3f& s);
  // Rotation by `degrees` about `axis` (right-handed, axis need not be unit).
  static Transform rotate(float degrees, const Vec3f& axis);
  // Camera-style frame: maps world to a frame looking down -z from `eye` (like gluLookAt).
  static Transform lookAt(const Vec3f& eye, const Vec3f& target, const Vec3f& up);

  Transform operator*(const Transform& o) const {
    return {matrix_ * o.matrix_, o.inverse_ * inverse_};
  }
  Transform inverse() const { return {inverse_, matrix_}; }

  Vec3f point(const Vec3f& p) const;
  Vec3f vector(const Vec3f& v) const;
  // Normals transform by the inverse transpose.
  Vec3f normal(const Vec3f& n) const;
  // True if the transform flips handedness (negative determinant of the linear part).
  bool swapsHandedness() const;

  const Mat4& matrix() const { return matrix_; }
  const Mat4& inverseMatrix() const { return inverse_; }

 private:
  Mat4 matrix_;
  Mat4 inverse_;
};

}  // namespace parallax
