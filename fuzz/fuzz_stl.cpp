// STL, ASCII and binary, written as fuzz.stl.
#include "fuzz_mesh_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace parallax::fuzz;
  return loadMesh(writeScratch("fuzz.stl", asText(data, size)));
}
