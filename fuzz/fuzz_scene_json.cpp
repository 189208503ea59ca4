// Scene files (docs/scene-format.md) through io::loadScene. The scratch folder also holds a
// small texture (textures/uv-grid.png, as the examples name it) and a small mesh (mesh.obj), so
// that inputs that reference them reach the image and mesh readers as a scene would.
#include <string>

#include "fuzz_support.h"
#include "parallax/image/image.h"
#include "parallax/importer/scene_file.h"
#include "parallax/io/image_file.h"

namespace {

void writeCompanions() {
  static const bool done = [] {
    parallax::Image grid(4, 4);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) grid.at(x, y) = parallax::Vec3f((x + y) % 2 ? 0.9f : 0.1f);
    parallax::fuzz::writeScratch("textures/uv-grid.png", parallax::pngBytes(grid));
    parallax::fuzz::writeScratch("mesh.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                                 "f 1/1 2/2 3/3\nf 1 3 4\n");
    return true;
  }();
  (void)done;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  writeCompanions();
  const std::string path =
      parallax::fuzz::writeScratch("scene.json", parallax::fuzz::asText(data, size));
  return parallax::fuzz::refuseCleanly([&] { parallax::loadScene(path); });
}
