// PLY, ASCII and binary (either byte order), written as fuzz.ply.
#include "fuzz_mesh_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace parallax::fuzz;
  return loadMesh(writeScratch("fuzz.ply", asText(data, size)));
}
