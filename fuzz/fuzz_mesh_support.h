// The mesh targets: the input written under a mesh file name and read by io::loadMeshFile, as
// a scene's mesh object or a bare mesh on the command line would be.
#pragma once

#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "parallax/image/image.h"
#include "parallax/importer/mesh_file.h"
#include "parallax/io/image_file.h"
#include "parallax/scene/scene.h"

namespace parallax::fuzz {

inline int loadMesh(const std::string& path) {
  return refuseCleanly([&] {
    Scene scene;
    loadMeshFile(path, {}, scene);
  });
}

// A small PNG for the textures that OBJ materials and glTF images may name ("texture.png").
inline void writeTexture() {
  static const bool done = [] {
    Image checker(4, 4);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) checker.at(x, y) = Vec3f((x + y) % 2 ? 0.9f : 0.1f);
    writeScratch("texture.png", pngBytes(checker));
    return true;
  }();
  (void)done;
}

}  // namespace parallax::fuzz
