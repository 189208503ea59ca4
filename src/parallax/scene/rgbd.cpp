#include "parallax/scene/rgbd.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "parallax/core/parallel.h"

namespace parallax {

namespace {

double tanHalfFov(float fovDegrees) {
  return std::tan(0.5 * double(fovDegrees) * double(kPi) / 180.0);
}

void checkOptions(const RgbdOptions& o) {
  if (!(o.nearDistance > 0.0f) || !(o.farDistance > o.nearDistance) ||
      !std::isfinite(o.farDistance))
    throw std::invalid_argument("makeRgbdScene: the range needs 0 < near < far");
  if (!(o.fovDegrees > 0.0f && o.fovDegrees < 180.0f))
    throw std::invalid_argument("makeRgbdScene: the field of view must be in (0, 180) degrees");
  if (!(o.edgeJump > 0.0f) || !(o.backgroundOffset > 0.0f) || o.backgroundRadius < 0)
    throw std::invalid_argument("makeRgbdScene: layered edge settings out of range");
}

// Each pixel's distance z along the axis.
std::vector<float> distances(const DepthMap& depth, const RgbdOptions& options) {
  std::vector<float> z(depth.values.size());
  for (size_t i = 0; i < z.size(); ++i) z[i] = depthFromValue(depth.values[i], options);
  return z;
}

// One sheet: a vertex per pixel centre at distance z[i] * scale along its ray, UVs at the
// texel centres, two triangles per 2 x 2 block of centres unless `cut` says the block spans a
// depth edge. The triangles (a, c, b) and (b, c, d) of the block a b / c d face +z (cross of
// c - a = down and b - a = right is +z), toward the camera.
TriangleMesh makeSheet(const std::string& name, uint32_t material, const std::vector<float>& z,
                       int width, int height, const RgbdOptions& options, float scale,
                       float cutJump) {
  TriangleMesh mesh;
  mesh.name = name;
  mesh.material = material;
  const size_t count = size_t(width) * size_t(height);
  mesh.positions.resize(count);
  mesh.uvs.resize(count);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      const float fx = float(x) + 0.5f, fy = float(y) + 0.5f;
      mesh.positions[i] = unprojectFilm(fx, fy, z[i] * scale, width, height, options.fovDegrees);
      // Image::sampleBilinear: texel centres at (i + 0.5) / width, v = 1 at row 0; at the
      // pixel centres the lookup never reaches across the wrapped edge.
      mesh.uvs[i] = {fx / float(width), 1.0f - fy / float(height)};
    }
  mesh.indices.reserve(size_t(width - 1) * size_t(height - 1) * 6);
  for (int y = 0; y + 1 < height; ++y)
    for (int x = 0; x + 1 < width; ++x) {
      const uint32_t a = uint32_t(y * width + x), b = a + 1, c = a + uint32_t(width), d = c + 1;
      if (cutJump > 0.0f) {
        const float lo = std::min({z[a], z[b], z[c], z[d]});
        const float hi = std::max({z[a], z[b], z[c], z[d]});
        if (hi - lo > cutJump * lo) continue;
      }
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  return mesh;
}

// For each i of a line of n items, the index of the largest value(j) over the window
// j in [i - r, i + r] (clipped to the line), ties to the smallest j: a sliding maximum with a
// deque of candidates whose values decrease (equal values keep their order), so that each item
// is pushed and popped once, whatever r. `deque` holds n ints.
template <class Value>
void slidingArgmax(int n, int r, const Value& value, int* deque, int* out) {
  int head = 0, tail = 0;
  for (int k = 0; k < n + r; ++k) {
    if (k < n) {
      const float v = value(k);
      while (tail > head && value(deque[tail - 1]) < v) --tail;
      deque[tail++] = k;
    }
    const int i = k - r;
    if (i < 0) continue;
    while (deque[head] < i - r) ++head;
    out[i] = deque[head];
  }
}

// The far-side dilation: for each pixel, the pixel of largest z within `radius` (a square
// window, clipped at the borders), ties to the first in scan order, found as a horizontal then
// a vertical pass (the maximum over a square is the maximum over rows of the row maxima; in
// both passes an earlier position is an earlier pixel in scan order). The passes run in
// parallel over rows, then columns; each result depends only on its window.
std::vector<size_t> farthestNearby(const std::vector<float>& z, int width, int height, int radius) {
  std::vector<size_t> rowBest(z.size()), best(z.size());
  parallelFor(height, 0, 8, [&](int64_t begin, int64_t end) {
    std::vector<int> deque(static_cast<size_t>(width)), pick(static_cast<size_t>(width));
    for (int64_t y = begin; y < end; ++y) {
      const size_t row = size_t(y) * size_t(width);
      slidingArgmax(
          width, radius, [&](int x) { return z[row + size_t(x)]; }, deque.data(), pick.data());
      for (int x = 0; x < width; ++x) rowBest[row + size_t(x)] = row + size_t(pick[size_t(x)]);
    }
  });
  parallelFor(width, 0, 8, [&](int64_t begin, int64_t end) {
    std::vector<int> deque(static_cast<size_t>(height)), pick(static_cast<size_t>(height));
    for (int64_t x = begin; x < end; ++x) {
      const auto at = [&](int y) { return size_t(y) * size_t(width) + size_t(x); };
      slidingArgmax(
          height, radius, [&](int y) { return z[rowBest[at(y)]]; }, deque.data(), pick.data());
      for (int y = 0; y < height; ++y) best[at(y)] = rowBest[at(pick[size_t(y)])];
    }
  });
  return best;
}

}  // namespace

const char* depthConventionName(DepthConvention convention) {
  switch (convention) {
    case DepthConvention::Disparity:
      return "disparity";
    case DepthConvention::Depth:
      return "depth";
    case DepthConvention::Inverse:
      return "inverse";
  }
  return "disparity";
}

const char* rgbdEdgesName(RgbdEdges edges) {
  return edges == RgbdEdges::Layered ? "layered" : "stretch";
}

float depthFromValue(float v, const RgbdOptions& options) {
  const double n = options.nearDistance, f = options.farDistance, value = v;
  switch (options.convention) {
    case DepthConvention::Disparity:
      // Linear in 1/z between 1/far (v = 0) and 1/near (v = 1).
      return float(1.0 / (value / n + (1.0 - value) / f));
    case DepthConvention::Depth:
      return float(n + value * (f - n));
    case DepthConvention::Inverse:
      return float(f - value * (f - n));
  }
  return float(f);
}

Vec3f unprojectFilm(float filmX, float filmY, float z, int width, int height, float fovDegrees) {
  const double t = tanHalfFov(fovDegrees);
  const double sx = 2.0 * double(filmX) / double(width) - 1.0;
  const double sy = 1.0 - 2.0 * double(filmY) / double(height);
  // Square pixels: the vertical half-extent at unit distance is t * height / width.
  return {float(sx * t * double(z)), float(sy * t * double(height) / double(width) * double(z)),
          -z};
}

float verticalFovDegrees(float fovDegrees, int width, int height) {
  const double t = tanHalfFov(fovDegrees) * double(height) / double(width);
  return float(2.0 * std::atan(t) * 180.0 / double(kPi));
}

int backgroundRadiusPx(const RgbdOptions& options, int width) {
  return options.backgroundRadius > 0 ? options.backgroundRadius : std::max(2, width / 64);
}

double rgbdSceneBytes(int width, int height, RgbdEdges edges) {
  // Per pixel and sheet: a position and a UV (20 bytes), two triangles (24 bytes), Embree's
  // copy of both (about 40 bytes), the texture (12 bytes); while building, the distances.
  const double pixels = double(width) * double(height);
  const double sheets = edges == RgbdEdges::Layered ? 2.0 : 1.0;
  return pixels * (sheets * (20.0 + 24.0 + 40.0 + 12.0) + 4.0 + (sheets - 1.0) * 8.0 * 2.0);
}

Scene makeRgbdScene(const Image& colour, const DepthMap& depth, const RgbdOptions& options,
                    const std::string& source) {
  checkOptions(options);
  const int width = colour.width(), height = colour.height();
  if (depth.width != width || depth.height != height ||
      depth.values.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("makeRgbdScene: the colour image and the depth map differ in size");
  if (width < 2 || height < 2)
    throw std::invalid_argument("makeRgbdScene: the photo needs at least 2 x 2 pixels");
  for (float v : depth.values)
    if (!(v >= 0.0f && v <= 1.0f))
      throw std::invalid_argument("makeRgbdScene: depth values must lie in [0, 1]");

  Scene scene;
  scene.source = source;
  const std::vector<float> z = distances(depth, options);
  const bool layered = options.edges == RgbdEdges::Layered;

  // The photo's colours exactly: albedo 1 times the texture, lit by ambient radiance 1 alone,
  // so each hit returns the texel (render/packet_tracer.cpp: emitted + albedo * ambient).
  scene.images.push_back(colour);
  Texture photo;
  photo.kind = Texture::Kind::Image;
  photo.image = 0;
  scene.textures.push_back(photo);
  Material material;
  material.name = "photo";
  material.diffuse = Vec3f(1.0f);
  material.diffuseTexture = 0;
  scene.materials.push_back(material);
  scene.meshes.push_back(
      makeSheet("photo", 0, z, width, height, options, 1.0f, layered ? options.edgeJump : 0.0f));

  if (layered) {
    // What the cut quads uncover is the far side's: each pixel of the background sheet takes
    // the depth and the colour of the farthest pixel near it, and sits a little farther along
    // its own ray, so that from the photo's viewpoint the main sheet hides it exactly.
    const int radius = backgroundRadiusPx(options, width);
    const std::vector<size_t> from = farthestNearby(z, width, height, radius);
    std::vector<float> farZ(z.size());
    Image farColour(width, height);
    for (size_t i = 0; i < z.size(); ++i) {
      farZ[i] = z[from[i]];
      farColour.pixels()[i] = colour.pixels()[from[i]];
    }
    scene.images.push_back(std::move(farColour));
    Texture behind = photo;
    behind.image = 1;
    scene.textures.push_back(behind);
    Material back = material;
    back.name = "background";
    back.diffuseTexture = 1;
    scene.materials.push_back(back);
    scene.meshes.push_back(makeSheet("background", 1, farZ, width, height, options,
                                     1.0f + options.backgroundOffset, 0.0f));
  }

  scene.lights.clear();
  scene.ambient = Vec3f(1.0f);
  scene.background = Vec3f(0.0f);
  scene.maxDepth = 0;  // nothing reflects

  // The display faces the viewer along +z, up +y, and fits the photo's bounds: with no width
  // given, the framing (camera/framing.h, Auto = Depth) scales the picture to the window and
  // compresses its depth into the display's depth budget.
  const Bounds3f bounds = scene.bounds();
  scene.display.center = bounds.center();
  scene.display.normal = {0, 0, 1};
  scene.display.up = {0, 1, 0};
  scene.display.width = bounds.diagonal().x;
  scene.display.fit = bounds;
  scene.display.content = bounds;
  scene.display.fitMode = DisplayFit::Auto;
  // The mesh lies inside the frustum of the field of view between its nearest and farthest z.
  for (float zEnd : {-bounds.hi.z, -bounds.lo.z})
    for (int corner = 0; corner < 4; ++corner)
      scene.display.contentHull.push_back(unprojectFilm((corner & 1) ? float(width) : 0.0f,
                                                        (corner & 2) ? float(height) : 0.0f, zEnd,
                                                        width, height, options.fovDegrees));
  scene.display.fillWindow = true;
  // `parallax view` sees it from the photo's own viewpoint, with the photo's field of view.
  CameraSpec camera;
  camera.eye = {0, 0, 0};
  camera.lookAt = {0, 0, -1};
  camera.up = {0, 1, 0};
  camera.fovDegrees = verticalFovDegrees(options.fovDegrees, width, height);
  scene.camera = camera;
  return scene;
}

}  // namespace parallax
