#include "parallax/layers/layer_method.h"

#include <array>
#include <utility>

namespace parallax {

namespace {
constexpr std::array<std::pair<LayerMethod, std::string_view>, 3> kNames = {{
    {LayerMethod::Slits, "slits"},
    {LayerMethod::OptimizedImage, "optimized-image"},
    {LayerMethod::Nmf, "nmf"},
}};
}  // namespace

std::string_view layerMethodName(LayerMethod method) {
  for (const auto& [m, name] : kNames)
    if (m == method) return name;
  return "?";
}

std::optional<LayerMethod> layerMethodNamed(std::string_view name) {
  for (const auto& [m, n] : kNames)
    if (n == name) return m;
  return std::nullopt;
}

}  // namespace parallax
