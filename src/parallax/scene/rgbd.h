// RGB-D photos as scenes (docs/rgbd.md): a colour image and a depth map become a displaced
// height field seen by a pinhole at the origin looking down -z, textured with the photo and lit
// by ambient light alone, so that the render shows the photo's colours exactly.
#pragma once

#include <string>
#include <vector>

#include "parallax/core/math.h"
#include "parallax/image/image.h"
#include "parallax/scene/scene.h"

namespace parallax {

// How a depth map's value v in [0, 1] gives the distance z along the optical axis (docs/rgbd.md):
//   Disparity: v is proportional to 1/z, bright = near (MiDaS, Depth-Anything):
//              z = 1 / (v / near + (1 - v) / far)
//   Depth:     v is the distance, dark = near: z = near + v (far - near)
//   Inverse:   bright = near, linear in depth: z = far - v (far - near)
enum class DepthConvention { Disparity, Depth, Inverse };

// Stretch: every pair of neighbouring pixels is connected, so depth jumps become rubber sheets.
// Layered: quads whose corners' depths jump are cut, and a background sheet (the depth map
// dilated toward the far side, the colours extended from the far side) fills what they uncover.
enum class RgbdEdges { Stretch, Layered };

struct RgbdOptions {
  DepthConvention convention = DepthConvention::Disparity;
  // The distances (scene units, along the optical axis) of the values 1 and 0 of Disparity and
  // Inverse, of 0 and 1 of Depth. Only the ratio far / near shapes the scene: the framing
  // scales it to the display (docs/rgbd.md, "Range"). 0 < near < far.
  float nearDistance = 1.0f;
  float farDistance = 3.0f;
  float fovDegrees = 50.0f;  // horizontal field of view of the photo, in (0, 180)
  RgbdEdges edges = RgbdEdges::Stretch;
  // Layered: a quad is cut when (largest z - smallest z) / smallest z of its corners exceeds this.
  float edgeJump = 0.05f;
  // Layered: the background sheet sits this fraction farther along each pixel's ray.
  float backgroundOffset = 0.01f;
  // Layered: the half-width in pixels of the far-side dilation; 0: max(2, width / 64).
  int backgroundRadius = 0;
};

// A depth map: width x height values in [0, 1], row 0 at the top (as the image).
struct DepthMap {
  int width = 0, height = 0;
  std::vector<float> values;
  float at(int x, int y) const { return values[size_t(y) * size_t(width) + size_t(x)]; }
};

const char* depthConventionName(DepthConvention convention);
const char* rgbdEdgesName(RgbdEdges edges);

// z (> 0, the distance in front of the camera along -z) of depth value v under the options'
// convention and range.
float depthFromValue(float v, const RgbdOptions& options);

// The point at film position (filmX, filmY) (continuous pixels, (0, 0) the top-left corner of a
// width x height photo) at distance z along the axis, for a pinhole at the origin looking down
// -z with up +y, square pixels and the horizontal field of view fovDegrees:
//   (x, y, -z) with x = (2 filmX / width - 1) tan(fov / 2) z,
//                   y = (1 - 2 filmY / height) tan(fov / 2) (height / width) z.
Vec3f unprojectFilm(float filmX, float filmY, float z, int width, int height, float fovDegrees);

// The vertical field of view (degrees) of a width x height photo with horizontal `fovDegrees`.
float verticalFovDegrees(float fovDegrees, int width, int height);

// Layered: the far-side dilation's half-width in pixels for a photo `width` pixels wide.
int backgroundRadiusPx(const RgbdOptions& options, int width);

// Rough bytes the scene of a width x height photo takes (meshes, texture images), for memory
// checks before it is built.
double rgbdSceneBytes(int width, int height, RgbdEdges edges);

// The scene: one vertex per pixel centre (film (x + 0.5, y + 0.5)), two triangles per 2 x 2 block
// of pixel centres, facing the camera; UVs at the pixel centres of the colour image. Material:
// the photo as a diffuse texture, albedo 1; no lights; ambient 1; background black. The display
// placement faces +z with up +y and fits the mesh bounds (DisplayFit::Auto, so the framing fits
// the picture to the window and its depth into the display's depth budget). `source` names the
// scene. Throws std::invalid_argument when the sizes differ or are below 2 x 2, a value is not in
// [0, 1], or the options are out of range (the io loader checks them first, naming the file).
Scene makeRgbdScene(const Image& colour, const DepthMap& depth, const RgbdOptions& options,
                    const std::string& source = "<rgbd>");

}  // namespace parallax
