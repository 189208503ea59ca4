// Quilt file names ("scene_qs5x9a1.7778.png", docs/quilts.md) through parseQuiltName, and the
// "CxR" layouts of --quilt and --quilt-layout through parseColumnsByRows. A parsed name must
// survive the round trip through quiltFileName.
#include <cstdlib>
#include <string>

#include "fuzz_support.h"
#include "parallax/render/quilt.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace parallax::fuzz;
  const std::string text(asText(data, size));
  int columns = 0, rows = 0;
  if (parallax::parseColumnsByRows(text, columns, rows) &&
      (columns < 1 || rows < 1 || columns > 1024 || rows > 1024))
    std::abort();  // the documented range
  return refuseCleanly([&] {
    const parallax::QuiltLayout layout = parallax::parseQuiltName(text);
    const parallax::QuiltLayout again =
        parallax::parseQuiltName(parallax::quiltFileName("q", layout, ".png"));
    if (again.columns != layout.columns || again.rows != layout.rows) std::abort();
  });
}
