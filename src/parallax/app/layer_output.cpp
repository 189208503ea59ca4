#include "parallax/app/layer_output.h"

#include <cstdio>
#include <ctime>

#include "parallax/io/display_file.h"
#include "parallax/io/image_file.h"

namespace parallax::app {

namespace {

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

}  // namespace

void startRenderRecord(JsonWriter& record, const std::string& method,
                       const std::string& displayFile) {
  record.set("/program", "parallax");
  record.set("/version", PARALLAX_VERSION);
  record.set("/created", utcNow());
  record.set("/method", method);
  record.set("/display_file", displayFile.empty() ? std::string("<built-in>") : displayFile);
}

// DIR/image.png, mask.png (image.pfm with `linear`), display.json and
// render.json (the record, with /outputs and /design added).
void writeDisplayLayers(const std::string& output, const Image& image, const Image& mask,
                        const DisplayDesign& design, bool linear, JsonWriter& record) {
  record.set("/outputs/image", "image.png");
  record.set("/outputs/mask", "mask.png");
  record.set("/outputs/display", "display.json");
  if (linear) record.set("/outputs/image_linear", "image.pfm");
  writeDesignJson(record, "/design", design);

  const std::string dir = output.empty() ? "." : output;
  writeImage(dir + "/image.png", image);
  writeImage(dir + "/mask.png", mask);
  if (linear) writeImage(dir + "/image.pfm", image);
  // The display as a display file, so that `simulate DIR` and other tools can read it back.
  writeFileAtomically(dir + "/display.json", displayFileText(design.spec));
  writeFileAtomically(dir + "/render.json", record.dump() + "\n");
  std::printf("wrote %s/image.png (%dx%d), %s/mask.png (%dx%d), %s/render.json\n", dir.c_str(),
              image.width(), image.height(), dir.c_str(), mask.width(), mask.height(), dir.c_str());
}

}  // namespace parallax::app
