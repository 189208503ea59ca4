// Built-in calibrations of the common Looking Glass devices, selectable by name
// (`--display lkg:portrait`). Each is the device family's template as Looking Glass's toolkit
// ships it (LKG-Toolkit, LKGDeviceTemplateSystem.cs, kept in step with Bridge): pitch, slope,
// center, view cone, DPI, screen size, subpixel cells, and the family's default quilt. A real
// unit's own visual.json differs slightly (its measured center and pitch) and renders sharper.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "parallax/display/lenticular.h"

namespace parallax {

struct LenticularPreset {
  std::string name;         // as given after "lkg:"
  std::string description;  // the device, and its serial-number prefix
  LenticularCalibration calibration;
};

const std::vector<LenticularPreset>& lenticularPresets();
// The preset of that name; nullopt if there is none.
std::optional<LenticularCalibration> lenticularPreset(const std::string& name);
// "portrait, go, ..." for messages.
std::string lenticularPresetNames();

}  // namespace parallax
