// Display files: the JSON description of a two-layer display (docs/display-format.md), and the
// JSON form of a derived design for reports.
#pragma once

#include <string>

#include "parallax/display/display.h"
#include "parallax/io/json_writer.h"

namespace parallax {

// Reads a display file. Unknown keys and wrong types throw InputError naming the file and key;
// relations between values are checked by designDisplay (which names the same file).
DisplaySpec loadDisplayFile(const std::string& path);
// The spec as a display file that loadDisplayFile reads back (used by calibrate apply).
std::string displayFileText(const DisplaySpec& spec);

// Writes every given and derived figure of a design under the JSON pointer `at` ("" = root).
void writeDesignJson(JsonWriter& json, const std::string& at, const DisplayDesign& design);

}  // namespace parallax
