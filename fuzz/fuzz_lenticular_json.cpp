// Lenticular calibrations (Looking Glass visual.json, docs/lenticular.md) through the in-memory
// parseLenticularCalibration, and the design derived from what it accepts.
#include <string>

#include "fuzz_support.h"
#include "parallax/display/lenticular.h"
#include "parallax/io/lenticular_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(parallax::fuzz::asText(data, size));
  return parallax::fuzz::refuseCleanly([&] {
    parallax::designLenticular(parallax::parseLenticularCalibration(text, "visual.json"));
  });
}
