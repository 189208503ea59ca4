#include "parallax/scene/look.h"

#include <algorithm>
#include <cmath>

namespace parallax {

namespace {

// The filmic log encoding: 16.5 stops, 10 below middle grey and 6.5 above (Blender's Filmic).
constexpr double kMiddleGrey = 0.18, kStopsBelow = 10.0, kStops = 16.5;
// The S-curve's slope, and k: f(L_grey) = S(0.18) = 0.4614 (sRGB code of middle grey), so
// (k (1 - L) / L)^s = 1 / 0.4614 - 1 at L = 10 / 16.5.
constexpr double kContrast = 1.6;

double srgbDecode(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

double curveScale() {
  const double grey = 1.055 * std::pow(kMiddleGrey, 1 / 2.4) - 0.055;  // 0.4614
  const double lGrey = kStopsBelow / kStops;
  return std::pow(1.0 / grey - 1.0, 1.0 / kContrast) * lGrey / (1.0 - lGrey);
}

}  // namespace

float filmicCurve(float x) {
  if (!(x > 0.0f)) return 0.0f;
  static const double k = curveScale();
  const double l =
      std::clamp((std::log2(double(x) / kMiddleGrey) + kStopsBelow) / kStops, 0.0, 1.0);
  if (l <= 0.0) return 0.0f;
  if (l >= 1.0) return 1.0f;
  const double encoded = 1.0 / (1.0 + std::pow(k * (1.0 - l) / l, kContrast));
  return float(srgbDecode(encoded));
}

Vec3f Look::apply(const Vec3f& radiance) const {
  const float gain = float(std::exp2(exposureStops));
  Vec3f exposed = radiance * gain;
  if (transform == ViewTransform::Filmic)
    exposed = Vec3f(filmicCurve(exposed.x), filmicCurve(exposed.y), filmicCurve(exposed.z));
  return exposed;
}

std::optional<ViewTransform> parseViewTransform(const std::string& name) {
  if (name == "standard") return ViewTransform::Standard;
  if (name == "filmic") return ViewTransform::Filmic;
  return std::nullopt;
}

const char* viewTransformName(ViewTransform transform) {
  return transform == ViewTransform::Filmic ? "filmic" : "standard";
}

}  // namespace parallax
