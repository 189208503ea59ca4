// Lenticular calibration files (visual.json, docs/lenticular.md): devices write each field as
// {"value": number}; plain numbers are accepted too. A missing required field or a wrong type
// throws InputError naming the file and the key; fields Looking Glass's shaders default (invView,
// viewCone) are defaulted the same way and unknown keys ignored, each noted in
// calibration.warnings.
#pragma once

#include <string>

#include "parallax/display/lenticular.h"
#include "parallax/io/json_reader.h"
#include "parallax/io/json_writer.h"

namespace parallax {

LenticularCalibration loadLenticularCalibration(const std::string& path);
LenticularCalibration parseLenticularCalibration(const std::string& text, const std::string& file);
LenticularCalibration readLenticularCalibration(const JsonReader& root);

// The calibration in the devices' format ({"value": n} fields), read back by the loader.
std::string lenticularCalibrationText(const LenticularCalibration& calibration);

// Every given and derived figure of a design under the JSON pointer `at` ("" = root).
void writeLenticularDesignJson(JsonWriter& json, const std::string& at,
                               const LenticularDesign& design);

}  // namespace parallax
