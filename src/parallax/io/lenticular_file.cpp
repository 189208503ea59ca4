#include "parallax/io/lenticular_file.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/display/lenticular_presets.h"
#include "parallax/io/json_reader.h"

namespace parallax {

namespace {

// A field as devices write it, {"value": n}, or a plain number.
double fieldNumber(const JsonReader& node) {
  if (!node.isObject()) return node.number();
  node.expectObject({"value"});
  return node["value"].number();
}

JsonReader present(const JsonReader& root, const char* key) {
  if (!root.has(key)) throw InputError(root.file(), root.pointer() + "/" + key, "missing");
  return root[key];
}

double required(const JsonReader& root, const char* key) {
  return fieldNumber(present(root, key));
}

// Flags are numbers 0 or 1 in device files (JSON booleans accepted as well).
bool flag(const JsonReader& node) {
  if (node.isObject()) {
    node.expectObject({"value"});
    return flag(node["value"]);
  }
  if (!node.isNumber()) return node.boolean();
  const double v = node.number();
  if (v != 0 && v != 1) node.fail("expected 0 or 1, found " + node.dump());
  return v == 1;
}

int pixels(const JsonReader& root, const char* key) {
  const double v = required(root, key);
  if (!(v >= 1 && v <= 65536 && v == std::floor(v)))
    root[key].fail("expected a whole number of pixels from 1 to 65536");
  return int(v);
}

SubpixelCell readCell(const JsonReader& node) {
  node.expectObject({"ROffsetX", "ROffsetY", "GOffsetX", "GOffsetY", "BOffsetX", "BOffsetY"});
  SubpixelCell cell;
  const char* names[3][2] = {
      {"ROffsetX", "ROffsetY"}, {"GOffsetX", "GOffsetY"}, {"BOffsetX", "BOffsetY"}};
  for (size_t c = 0; c < 3; ++c) {
    cell.offsetX[c] = required(node, names[c][0]);
    cell.offsetY[c] = required(node, names[c][1]);
  }
  return cell;
}

// The keys of the published calibration format. Looking Glass's own readers merge a device's
// file over defaults and ignore keys they do not know, so newer firmware's keys are warnings
// here, not errors.
const std::vector<std::string> kKnownKeys = {
    "configVersion",   "serial",          "pitch",        "slope",         "center",
    "fringe",          "viewCone",        "invView",      "verticalAngle", "DPI",
    "screenW",         "screenH",         "flipImageX",   "flipImageY",    "flipSubp",
    "CellPatternMode", "cellPatternMode", "subpixelCells"};

// Defaults of the fields a device may leave out, as Looking Glass's WebXR library sets them
// (LookingGlassConfig: invView 1, viewCone 40 degrees, flips 0, CellPatternMode 0). The modern
// interlacing shader always takes 1 - fract(phase), the invView = 1 of older shaders.
constexpr bool kDefaultInvView = true;
constexpr double kDefaultViewConeDegrees = 40.0;

LenticularCalibration readCalibration(const JsonReader& root) {
  if (!root.isObject()) root.fail("expected a calibration object, found " + root.typeName());
  LenticularCalibration c;
  c.source = root.file();
  for (const auto& [key, value] : root.members())
    if (std::find(kKnownKeys.begin(), kKnownKeys.end(), key) == kKnownKeys.end())
      c.warnings.push_back(root.file() + ": /" + key + ": unknown key, ignored");
  c.pitch = required(root, "pitch");
  c.slope = required(root, "slope");
  c.center = required(root, "center");
  const auto defaulted = [&](const char* key, const std::string& value) {
    c.warnings.push_back(root.file() + ": /" + key + ": missing, taken as " + value +
                         " as Looking Glass's shaders do");
  };
  if (root.has("viewCone")) {
    c.viewConeDegrees = fieldNumber(root["viewCone"]);
  } else {
    c.viewConeDegrees = kDefaultViewConeDegrees;
    defaulted("viewCone", "40 degrees");
  }
  for (const char* unused : {"fringe", "verticalAngle"})
    if (root.has(unused)) fieldNumber(root[unused]);  // checked, though not used
  c.dpi = required(root, "DPI");
  c.screenW = pixels(root, "screenW");
  c.screenH = pixels(root, "screenH");
  if (root.has("invView")) {
    c.invView = flag(root["invView"]);
  } else {
    c.invView = kDefaultInvView;
    defaulted("invView", "1");
  }
  const auto optionalFlag = [&root](const char* key) { return root.has(key) && flag(root[key]); };
  c.flipImageX = optionalFlag("flipImageX");
  c.flipImageY = optionalFlag("flipImageY");
  c.flipSubpixels = optionalFlag("flipSubp");
  for (const char* key : {"CellPatternMode", "cellPatternMode"})
    if (root.has(key)) {
      const double mode = fieldNumber(root[key]);
      if (!(mode >= 0 && mode <= kCellPatternModes - 1 && mode == std::floor(mode)))
        root[key].fail("expected a cell pattern from 0 to 4, found " + root[key].dump());
      c.cellPatternMode = int(mode);
    }
  if (const auto cells = root.find("subpixelCells"))
    for (const JsonReader& cell : cells->elements()) c.subpixelCells.push_back(readCell(cell));
  // The serial is a string in device files; some tools write it as {"value": "..."}.
  if (const auto serial = root.find("serial")) {
    const JsonReader text = serial->isObject() ? (*serial)["value"] : *serial;
    if (text.isString()) c.serial = text.string();
  }
  designLenticular(c);  // the relations between fields, reported against this file
  // The unit's device, and with it its default quilt (not in visual.json).
  applyDeviceConventions(c);
  return c;
}

}  // namespace

LenticularCalibration readLenticularCalibration(const JsonReader& root) {
  return readCalibration(root);
}

LenticularCalibration parseLenticularCalibration(const std::string& text, const std::string& file) {
  return readCalibration(JsonDocument::parseText(text, file).root());
}

LenticularCalibration loadLenticularCalibration(const std::string& path) {
  return readCalibration(JsonDocument::parseFile(path).root());  // missing file: InputError
}

std::string lenticularCalibrationText(const LenticularCalibration& c) {
  JsonWriter json;
  // The serial is the unit's name (and its device's: display/lenticular_presets.h), kept so the
  // copy written beside the pictures is recognised as the same device.
  if (!c.serial.empty()) json.set("/serial", c.serial);
  const auto value = [&json](const char* key, double v) {
    json.set(std::string("/") + key + "/value", v);
  };
  value("pitch", c.pitch);
  value("slope", c.slope);
  value("center", c.center);
  value("viewCone", c.viewConeDegrees);
  value("invView", c.invView ? 1.0 : 0.0);
  value("DPI", c.dpi);
  value("screenW", double(c.screenW));
  value("screenH", double(c.screenH));
  value("flipImageX", c.flipImageX ? 1.0 : 0.0);
  value("flipImageY", c.flipImageY ? 1.0 : 0.0);
  value("flipSubp", c.flipSubpixels ? 1.0 : 0.0);
  value("CellPatternMode", double(c.cellPatternMode));
  json.setEmptyArray("/subpixelCells");
  const char* names[3] = {"R", "G", "B"};
  for (size_t i = 0; i < c.subpixelCells.size(); ++i)
    for (size_t ch = 0; ch < 3; ++ch) {
      const std::string at = "/subpixelCells/" + std::to_string(i) + "/" + names[ch];
      json.set(at + "OffsetX", c.subpixelCells[i].offsetX[ch]);
      json.set(at + "OffsetY", c.subpixelCells[i].offsetY[ch]);
    }
  return json.dump() + "\n";
}

void writeLenticularDesignJson(JsonWriter& json, const std::string& at, const LenticularDesign& d) {
  json.set(at + "/calibration_file", d.calibration.source);
  json.set(at + "/screen_w_px", d.calibration.screenW);
  json.set(at + "/screen_h_px", d.calibration.screenH);
  json.set(at + "/pixel_pitch_mm", d.pixelPitchMm);
  json.set(at + "/width_mm", d.widthMm);
  json.set(at + "/height_mm", d.heightMm);
  json.set(at + "/pitch_px", d.pitchPx);
  json.set(at + "/tilt", d.tilt);
  json.set(at + "/center", d.calibration.center);
  json.set(at + "/inv_view", d.calibration.invView);
  json.set(at + "/lens_slant_deg", d.lensSlantDegrees);
  json.set(at + "/lens_pitch_mm", d.lensPitchMm);
  json.set(at + "/horizontal_lens_pitch_mm", d.horizontalLensPitchMm);
  json.set(at + "/pixels_per_lens", d.pixelsPerLens);
  json.set(at + "/subpixels_per_lens", d.subpixelsPerLens);
  json.set(at + "/lenticules", d.lenticuleCount);
  json.set(at + "/view_cone_deg", d.calibration.viewConeDegrees);
  json.set(at + "/view_distance_mm", d.viewDistanceMm);
  json.set(at + "/view_zone_width_mm", d.viewZoneWidthMm);
  json.set(at + "/subpixel_cells", int(d.calibration.subpixelCells.size()));
  const LenticularCalibration& c = d.calibration;
  if (!c.serial.empty()) json.set(at + "/serial", c.serial);
  json.set(at + "/device", c.device.empty() ? "unknown" : "lkg:" + c.device);
  if (!c.deviceBasis.empty()) json.set(at + "/device_recognised_by", c.deviceBasis);
  json.set(at + "/default_quilt",
           std::to_string(c.quilt.columns) + "x" + std::to_string(c.quilt.rows) + " on " +
               std::to_string(c.quilt.width) + "x" + std::to_string(c.quilt.height));
  json.set(at + "/quilt_views", d.quiltViews);
  // The optics the pictures were made for (docs/lenticular.md, "The optics").
  json.set(at + "/optics/bundles", std::string(lensBundlesName(d.optics.bundles)));
  if (d.optics.bundles == LensBundles::Converging)
    json.set(at + "/optics/convergence_distance_mm", d.optics.convergenceDistanceMm);
  json.set(at + "/optics/lens_spot_subpixels", d.optics.spotWidthSubpixels);
}

}  // namespace parallax
