// OFF (ASCII; binary OFF is refused), written as fuzz.off.
#include "fuzz_mesh_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace parallax::fuzz;
  return loadMesh(writeScratch("fuzz.off", asText(data, size)));
}
