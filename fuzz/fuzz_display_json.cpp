// Display files (docs/display-format.md) through io::loadDisplayFile, and the design derived
// from what it accepts (designDisplay checks the relations between the values).
#include <string>

#include "fuzz_support.h"
#include "parallax/display/display.h"
#include "parallax/io/display_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path =
      parallax::fuzz::writeScratch("display.json", parallax::fuzz::asText(data, size));
  return parallax::fuzz::refuseCleanly([&] {
    const parallax::BarrierDisplayFile file = parallax::loadDisplayFile(path);
    parallax::designDisplay(file.spec, file.camera);
  });
}
