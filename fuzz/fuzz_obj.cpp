// Wavefront OBJ with its MTL: the input is the OBJ text, optionally followed by a line
// "#--mtl--" and the MTL text, written as fuzz.obj and fuzz.mtl ("mtllib fuzz.mtl" finds it;
// "map_Kd texture.png" finds a small PNG).
#include <string>

#include "fuzz_mesh_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace parallax::fuzz;
  writeTexture();
  const auto [obj, mtl] = splitAt(asText(data, size), "\n#--mtl--\n");
  writeScratch("fuzz.mtl", mtl);
  return loadMesh(writeScratch("fuzz.obj", obj));
}
