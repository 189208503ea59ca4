// glTF 2.0: JSON (.gltf) or binary (.glb, chosen by its "glTF" magic as the reader does). The
// input may end in a line "#--bin--" followed by the bytes of an external buffer, written as
// fuzz.bin (a buffer with "uri": "fuzz.bin" reads it); images may name texture.png.
#include <string>

#include "fuzz_mesh_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace parallax::fuzz;
  writeTexture();
  const auto [model, bin] = splitAt(asText(data, size), "\n#--bin--\n");
  writeScratch("fuzz.bin", bin);
  const bool glb = model.substr(0, 4) == "glTF";
  return loadMesh(writeScratch(glb ? "fuzz.glb" : "fuzz.gltf", model));
}
