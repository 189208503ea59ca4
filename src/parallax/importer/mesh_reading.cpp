// The helpers every mesh reader shares (mesh_reading.h).
#include "parallax/importer/mesh_reading.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <sstream>

#include "parallax/io/input_file.h"

namespace parallax {
namespace meshio {

void fail(const std::string& path, const std::string& message) {
  throw inputError(path, "", message);
}

std::string readFileBytes(const std::string& path) {
  return readInputFile(path);
}

namespace {

// std::isspace of the "C" locale, inline: the call into the C library was a quarter of the
// time of reading an ASCII PLY (the dragon, docs/import.md).
bool isSpace(char c) {
  return c == ' ' || (c >= '\t' && c <= '\r');
}

}  // namespace

void TextTokens::skipSpace() {
  while (pos_ < text_.size() && isSpace(text_[pos_])) {
    if (text_[pos_] == '\n') ++line_;
    ++pos_;
  }
}

std::string_view TextTokens::next() {
  skipSpace();
  tokenLine_ = line_;
  const size_t begin = pos_;
  while (pos_ < text_.size() && !isSpace(text_[pos_])) ++pos_;
  return text_.substr(begin, pos_ - begin);
}

void TextTokens::skipLine() {
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
}

bool TextTokens::atEnd() {
  skipSpace();
  return pos_ >= text_.size();
}

bool parseNumber(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ptr != end) return false;
  if (ec == std::errc::result_out_of_range) {
    // from_chars leaves the value alone on overflow and underflow; strtod gives +-inf or 0.
    value = std::strtod(std::string(token).c_str(), nullptr);
    return true;
  }
  return ec == std::errc();
}

bool parseInteger(std::string_view token, int64_t& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return !token.empty() && ptr == end && ec == std::errc();
}

std::string numberText(double value) {
  if (std::isnan(value)) return "nan";
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

namespace {

// Twice the signed area of the 2-D triangle (a, b, c); positive if it turns counter-clockwise.
float orient(const Vec2f& a, const Vec2f& b, const Vec2f& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool inTriangle(const Vec2f& p, const Vec2f& a, const Vec2f& b, const Vec2f& c) {
  return orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0;
}

}  // namespace

void triangulatePolygon(const std::vector<Vec3f>& positions, const std::vector<uint32_t>& corners,
                        std::vector<uint32_t>& out) {
  const size_t n = corners.size();
  auto emit = [&](size_t a, size_t b, size_t c) {
    out.insert(out.end(), {corners[a], corners[b], corners[c]});
  };
  auto fan = [&](const std::vector<size_t>& ring) {
    for (size_t k = 1; k + 1 < ring.size(); ++k) emit(ring[0], ring[k], ring[k + 1]);
  };
  std::vector<size_t> ring(n);
  for (size_t i = 0; i < n; ++i) ring[i] = i;
  if (n <= 3) return fan(ring);

  // Newell's method gives the normal of a concave or slightly non-planar polygon. Projecting
  // along its dominant axis onto the two cyclically following axes keeps the polygon
  // counter-clockwise when that component is positive; flip v when it is negative.
  Vec3f normal(0.0f);
  for (size_t i = 0; i < n; ++i) {
    const Vec3f& p = positions[corners[i]];
    const Vec3f& q = positions[corners[(i + 1) % n]];
    normal +=
        Vec3f((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x), (p.x - q.x) * (p.y + q.y));
  }
  int drop = 0;
  for (int axis = 1; axis < 3; ++axis)
    if (std::abs(normal[axis]) > std::abs(normal[drop])) drop = axis;
  if (!(std::abs(normal[drop]) > 0)) return fan(ring);  // no area (or NaN): nothing to clip
  const float flip = normal[drop] < 0 ? -1.0f : 1.0f;
  std::vector<Vec2f> p(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3f& q = positions[corners[i]];
    p[i] = {q[(drop + 1) % 3], flip * q[(drop + 2) % 3]};
  }

  bool convex = true;
  for (size_t i = 0; i < n && convex; ++i)
    convex = orient(p[(i + n - 1) % n], p[i], p[(i + 1) % n]) >= 0;
  if (convex) {
    auto q = [&](size_t i) -> const Vec3f& { return positions[corners[i]]; };
    if (n == 4 && length(q(3) - q(1)) < length(q(2) - q(0))) {
      emit(0, 1, 3);
      emit(1, 2, 3);
      return;
    }
    return fan(ring);
  }

  // Ear clipping (Eberly, "Triangulation by Ear Clipping"): cut off a convex corner whose
  // triangle contains no other corner, until a triangle is left.
  while (ring.size() > 3) {
    const size_t m = ring.size();
    bool clipped = false;
    for (size_t k = 0; k < m && !clipped; ++k) {
      const size_t a = ring[(k + m - 1) % m], b = ring[k], c = ring[(k + 1) % m];
      if (orient(p[a], p[b], p[c]) <= 0) continue;
      bool empty = true;
      for (size_t j : ring) {
        const bool corner = j == a || j == b || j == c;
        const bool sharesPosition = positions[corners[j]] == positions[corners[a]] ||
                                    positions[corners[j]] == positions[corners[b]] ||
                                    positions[corners[j]] == positions[corners[c]];
        if (!corner && !sharesPosition && inTriangle(p[j], p[a], p[b], p[c])) empty = false;
      }
      if (!empty) continue;
      emit(a, b, c);
      ring.erase(ring.begin() + std::ptrdiff_t(k));
      clipped = true;
    }
    if (!clipped) break;  // self-intersecting: fan what is left
  }
  fan(ring);
}

}  // namespace meshio

}  // namespace parallax
