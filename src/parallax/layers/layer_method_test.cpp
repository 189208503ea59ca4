#include "parallax/layers/layer_method.h"

#include <gtest/gtest.h>

namespace parallax {
namespace {

TEST(LayerMethod, EachNameParsesToItsMethodAndBack) {
  for (const LayerMethod method :
       {LayerMethod::Slits, LayerMethod::OptimizedImage, LayerMethod::Nmf}) {
    const std::optional<LayerMethod> parsed = layerMethodNamed(layerMethodName(method));
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(*parsed, method);
  }
  EXPECT_EQ(layerMethodNamed("optimized-image"), LayerMethod::OptimizedImage);
  EXPECT_EQ(layerMethodNamed("nmf"), LayerMethod::Nmf);
  EXPECT_FALSE(layerMethodNamed("NMF").has_value());
  EXPECT_FALSE(layerMethodNamed("").has_value());
  EXPECT_FALSE(layerMethodNamed("optimized_image").has_value());
}

}  // namespace
}  // namespace parallax
