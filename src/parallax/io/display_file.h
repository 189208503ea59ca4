// Display files: the JSON description of a two-layer display (docs/display-format.md), and the
// JSON form of a derived design for reports.
#pragma once

#include <string>

#include "parallax/display/display.h"
#include "parallax/display/display_model.h"
#include "parallax/io/json_reader.h"
#include "parallax/io/json_writer.h"

namespace parallax {

// A barrier display file: the display (the physics) and the camera settings it may carry
// (subpixel_rays, virtual/gap_mm, virtual/distance_mm). designDisplay(spec, camera) designs it.
struct BarrierDisplayFile {
  DisplaySpec spec;
  BarrierCameraSettings camera;
};

// Reads a display file. Unknown keys and wrong types throw InputError naming the file and key;
// relations between values are checked by designDisplay (which names the same file).
BarrierDisplayFile loadDisplayFile(const std::string& path);
BarrierDisplayFile readDisplayFile(const JsonReader& root, const std::string& path);

// A display of any kind, as described: a barrier's spec or a lenticular calibration.
struct DisplayDescription {
  DisplayKind kind = DisplayKind::Barrier;
  DisplaySpec barrier;               // kind == Barrier
  BarrierCameraSettings camera;      // kind == Barrier: the file's subpixel_rays and virtual/
  LenticularCalibration lenticular;  // kind == Lenticular
  const std::string& source() const {
    return kind == DisplayKind::Barrier ? barrier.source : lenticular.source;
  }
};
// "" is the built-in barrier display; "lkg:NAME" a built-in Looking Glass preset
// (display/lenticular_presets.h); anything else a file: a barrier display file
// (docs/display-format.md) or a lenticular calibration (visual.json, docs/lenticular.md), told
// apart by content (a calibration has "pitch", "slope" or "DPI"). Throws InputError naming the
// file (or the preset) and the key.
DisplayDescription loadDisplayDescription(const std::string& pathOrPreset);
// The spec (and the camera settings) as a display file that loadDisplayFile reads back (used by
// calibrate apply and the render's display.json).
std::string displayFileText(const DisplaySpec& spec, const BarrierCameraSettings& camera = {});

// Writes every given and derived figure of a design under the JSON pointer `at` ("" = root).
void writeDesignJson(JsonWriter& json, const std::string& at, const DisplayDesign& design);
// A display of any kind's design under `at`: the barrier's above, a lenticular panel's
// (writeLenticularDesignJson); nothing for a kind without a file of its own.
void writeDisplayDesignJson(JsonWriter& json, const std::string& at, const DisplayModel& display);

}  // namespace parallax
