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
  std::string name;          // as given after "lkg:"
  std::string description;   // the device, and its serial-number prefix
  std::string serialPrefix;  // how its units' serials begin ("LKG-J")
  LenticularCalibration calibration;
};

const std::vector<LenticularPreset>& lenticularPresets();
// The preset of that name; nullopt if there is none.
std::optional<LenticularCalibration> lenticularPreset(const std::string& name);
// The device of the preset of that name ("Looking Glass Portrait (LKG-P)"); "" if none.
std::string lenticularPresetDescription(const std::string& name);
// "portrait, go, ..." for messages.
std::string lenticularPresetNames();

// Which preset's device a calibration (a unit's own visual.json) is: the preset whose serial
// prefix begins its serial and whose panel has its resolution; else the presets of its
// resolution and DPI (within 1%), the nearest in lens pitch (the 16" Gen2 and Gen3 share
// 3840x2160 at 283 DPI; their pitches are 50 and 44.72 lenses an inch). A Go turned landscape
// (serial LKG-E, 2560x1440) is no preset's panel: none.
struct RecognisedDevice {
  const LenticularPreset* preset = nullptr;  // null: no preset's device
  std::string basis;  // how: "serial LKG-J00332", "3840x2160 pixels at 283 DPI, pitch 44.7"
};
RecognisedDevice recogniseLenticularDevice(const LenticularCalibration& calibration);

// The default quilt of a panel no preset knows: C x R views (40 to 66, nearest 48) whose tiles on
// a square quilt have about the panel's aspect (R / C = screenW / screenH), the quilt's side
// about C quarter panel widths (2048 to 8192 pixels, a multiple of C and R where it can be), as
// Looking Glass's own quilts are (5x9 on 4096 for 16:9, 8x6 on 3360 for 3:4).
QuiltFormat derivedQuilt(int screenW, int screenH);

// A unit's calibration given its device's conventions: calibration.device (the preset's name,
// or "" when none), its basis, and its default quilt (the preset's, or derivedQuilt).
void applyDeviceConventions(LenticularCalibration& calibration);

}  // namespace parallax
