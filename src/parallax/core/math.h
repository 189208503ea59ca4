// Small vector types for geometry (float, as Embree uses) and axis-aligned bounds.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace parallax {

struct Vec2f {
  float x = 0, y = 0;
};

// Display-frame points in millimetres, where float's 24 bits would not do (a 0.09 mm pixel
// 600 mm away).
struct Vec3d {
  double x = 0, y = 0, z = 0;
};

struct Vec3f {
  float x = 0, y = 0, z = 0;

  constexpr Vec3f() = default;
  constexpr Vec3f(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3f(float s) : x(s), y(s), z(s) {}

  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3f operator-() const { return {-x, -y, -z}; }
  constexpr Vec3f& operator+=(const Vec3f& o) {
    x += o.x, y += o.y, z += o.z;
    return *this;
  }
  constexpr Vec3f& operator*=(float s) {
    x *= s, y *= s, z *= s;
    return *this;
  }
  constexpr bool operator==(const Vec3f&) const = default;
};

constexpr Vec3f operator+(const Vec3f& a, const Vec3f& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr Vec3f operator-(const Vec3f& a, const Vec3f& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
constexpr Vec3f operator*(const Vec3f& a, const Vec3f& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
constexpr Vec3f operator*(const Vec3f& a, float s) {
  return {a.x * s, a.y * s, a.z * s};
}
constexpr Vec3f operator*(float s, const Vec3f& a) {
  return a * s;
}
constexpr Vec3f operator/(const Vec3f& a, float s) {
  return a * (1.0f / s);
}

constexpr float dot(const Vec3f& a, const Vec3f& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3f cross(const Vec3f& a, const Vec3f& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const Vec3f& a) {
  return std::sqrt(dot(a, a));
}
inline Vec3f normalize(const Vec3f& a) {
  return a / length(a);
}
inline Vec3f min(const Vec3f& a, const Vec3f& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3f max(const Vec3f& a, const Vec3f& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline float maxComponent(const Vec3f& a) {
  return std::max(a.x, std::max(a.y, a.z));
}
inline bool isFinite(const Vec3f& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// An orthonormal basis (tangent, bitangent) around a unit normal, without branches on the
// sign that would make shading discontinuous (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited").
inline void orthonormalBasis(const Vec3f& n, Vec3f& t, Vec3f& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

struct Bounds3f {
  Vec3f lo{std::numeric_limits<float>::infinity()};
  Vec3f hi{-std::numeric_limits<float>::infinity()};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const Vec3f& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void extend(const Bounds3f& b) {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
  }
  Vec3f center() const { return (lo + hi) * 0.5f; }
  Vec3f diagonal() const { return hi - lo; }
};

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr double kPiD = 3.14159265358979323846;

}  // namespace parallax
