// The outputs shared by `render`, `render --quilt` and `interlace`: the display's two layer
// images with display.json and a render.json record of how they were made.
#pragma once

#include <string>

#include "parallax/display/display.h"
#include "parallax/image/image.h"
#include "parallax/io/json_writer.h"

namespace parallax::app {

// Program, version, time, method and display file at the top of a render.json record.
void startRenderRecord(JsonWriter& record, const std::string& method,
                       const std::string& displayFile);

// Writes DIR/image.png, mask.png (image.pfm with `linear`), display.json and render.json (the
// record, with /outputs and /design added), each atomically, and says where on stdout.
void writeDisplayLayers(const std::string& output, const Image& image, const Image& mask,
                        const DisplayDesign& design, bool linear, JsonWriter& record);

}  // namespace parallax::app
