// Which layers a barrier display shows (docs/content-adaptive.md): the paper's slits and their
// ray-traced image, or layers solved for eyes across the view zone. Parsed once from its name,
// as options and files spell it; the code past the request layer reads the enum.
#pragma once

#include <optional>
#include <string_view>

namespace parallax {

enum class LayerMethod {
  Slits,           // the slit mask and the ray-traced image (nothing solved)
  OptimizedImage,  // the image layer solved behind the same slits (optimizeImageLayer)
  Nmf,             // both layers of one or more frames solved (factorizeLayers)
};

// "slits", "optimized-image", "nmf".
std::string_view layerMethodName(LayerMethod method);
// The method of that name; none for any other text.
std::optional<LayerMethod> layerMethodNamed(std::string_view name);

}  // namespace parallax
