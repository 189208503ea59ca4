#include "parallax/io/rgbd_file.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "parallax/core/memory.h"
#include "parallax/io/image_file.h"
#include "parallax/io/input_file.h"

namespace parallax {

namespace {

std::string sizeText(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// The depth values, one per pixel, from the file's samples (see loadRgbdScene for what is
// accepted).
DepthMap depthFromSamples(const ImageSamples& s, const std::string& path) {
  DepthMap map;
  map.width = s.width;
  map.height = s.height;
  map.values.resize(size_t(s.width) * size_t(s.height));
  const size_t channels = size_t(s.channels);
  for (size_t i = 0; i < map.values.size(); ++i) {
    const float* p = s.samples.data() + i * channels;
    if (channels >= 3 && (p[1] != p[0] || p[2] != p[0])) {
      const int x = int(i % size_t(s.width)), y = int(i / size_t(s.width));
      throw inputError(path, "",
                       "a depth map must be greyscale, but pixel (" + std::to_string(x) + ", " +
                           std::to_string(y) +
                           ") has different red, green and blue (a colour-mapped picture of "
                           "depth? save the depth as a grey 8- or 16-bit PNG)");
    }
    const float v = p[0];
    if (!(v >= 0.0f && v <= 1.0f)) {
      const int x = int(i % size_t(s.width)), y = int(i / size_t(s.width));
      throw inputError(path, "",
                       "depth value " + std::to_string(v) + " at pixel (" + std::to_string(x) +
                           ", " + std::to_string(y) +
                           ") is outside [0, 1] (float depth maps must be normalised)");
    }
    map.values[i] = v;
  }
  return map;
}

}  // namespace

Scene loadRgbdScene(const std::string& colourPath, const std::string& depthPath,
                    const RgbdOptions& options, double memoryLimitBytes) {
  // The depth map first: one channel, the smallest of the two; its size bounds the rest.
  const DepthMap depth = depthFromSamples(readImageSamples(depthPath), depthPath);
  if (depth.width < 2 || depth.height < 2)
    throw inputError(depthPath, "",
                     "the photo needs at least 2x2 pixels, the depth map has " +
                         sizeText(depth.width, depth.height));
  const double limit =
      memoryLimitBytes > 0 ? memoryLimitBytes : defaultMemoryLimitBytes(physicalMemoryBytes());
  checkMemory(rgbdSceneBytes(depth.width, depth.height, options.edges), limit, depthPath,
              "the RGB-D scene of " + sizeText(depth.width, depth.height) + " pixels",
              "scale the photo and its depth map down");
  const Image colour = readImage(colourPath);
  if (colour.width() != depth.width || colour.height() != depth.height)
    throw inputError(depthPath, "",
                     "the depth map is " + sizeText(depth.width, depth.height) +
                         " pixels but the colour image " + colourPath + " is " +
                         sizeText(colour.width(), colour.height()) + ": they must match");

  Scene scene = makeRgbdScene(colour, depth, options, colourPath);
  float lo = depth.values[0], hi = depth.values[0];
  for (float v : depth.values) lo = std::min(lo, v), hi = std::max(hi, v);
  if (lo == hi)
    scene.warnings.push_back(depthPath + ": the depth map is constant (" + std::to_string(lo) +
                             "): the photo is a flat picture at one distance");
  return scene;
}

}  // namespace parallax
