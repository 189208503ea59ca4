#include "parallax/display/lenticular_presets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace parallax {

namespace {

struct Template {
  const char* name;
  const char* description;
  const char* serialPrefix;
  int screenW, screenH;
  double dpi, pitch, slope, center, viewCone;
  QuiltFormat quilt;
  int cellPatternMode;
  std::vector<SubpixelCell> cells;
};

LenticularPreset make(const Template& t) {
  LenticularCalibration c;
  c.source = std::string("lkg:") + t.name;
  c.pitch = t.pitch;
  c.slope = t.slope;
  c.center = t.center;
  c.viewConeDegrees = t.viewCone;
  c.dpi = t.dpi;
  c.screenW = t.screenW;
  c.screenH = t.screenH;
  c.invView = true;  // every template: the shaders' 1 - frac
  c.cellPatternMode = t.cellPatternMode;
  c.subpixelCells = t.cells;
  c.quilt = t.quilt;
  c.device = t.name;
  return {t.name, t.description, t.serialPrefix, c};
}

// The OLED panels' subpixel layouts (pixels, y up). 16" Gen3 landscape (and the 32" Gen3
// portrait template): the second cell mirrors the first in y, on alternate columns (pattern 2).
const std::vector<SubpixelCell> kGen3LandscapeCells = {{{-0.31, 0.28, 0.0}, {0.25, 0.25, -0.25}},
                                                       {{-0.31, 0.28, 0.0}, {-0.25, -0.25, 0.25}}};
// 16" Gen3 portrait: the same panel turned, the second cell mirrored in x on alternate rows
// (pattern 4).
const std::vector<SubpixelCell> kGen3PortraitCells = {{{-0.25, -0.25, 0.25}, {-0.31, 0.28, 0.0}},
                                                      {{0.25, 0.25, -0.25}, {-0.31, 0.28, 0.0}}};

std::vector<LenticularPreset> build() {
  const std::vector<Template> templates = {
      {"portrait",
       "Looking Glass Portrait (LKG-P)",
       "LKG-P",
       1536,
       2048,
       324,
       52,
       -7,
       0.5,
       40,
       {8, 6, 3360, 3360},
       0,
       {}},
      {"go",
       "Looking Glass Go (LKG-E)",
       "LKG-E",
       1440,
       2560,
       491,
       80.7,
       -6.3,
       -0.3,
       54,
       {11, 6, 4092, 4092},
       0,
       {}},
      {"16-gen2",
       "Looking Glass 16\" Gen2 (LKG-A)",
       "LKG-A",
       3840,
       2160,
       283,
       50,
       -7,
       0.5,
       40,
       {5, 9, 4096, 4096},
       0,
       {}},
      {"32-gen2",
       "Looking Glass 32\" Gen2 (LKG-B)",
       "LKG-B",
       7680,
       4320,
       280,
       42,
       -6,
       0.3,
       40,
       {5, 9, 8192, 8192},
       0,
       {}},
      {"65-gen2",
       "Looking Glass 65\" Gen2 (LKG-D)",
       "LKG-D",
       7680,
       4320,
       136,
       42,
       -6,
       0.3,
       40,
       {8, 9, 8192, 8192},
       0,
       {}},
      {"16-gen3",
       "Looking Glass 16\" Spatial Display, landscape (LKG-J)",
       "LKG-J",
       3840,
       2160,
       283,
       44.72,
       -6.9,
       0.5,
       50,
       {7, 7, 5999, 5999},
       2,
       kGen3LandscapeCells},
      {"16-gen3-portrait",
       "Looking Glass 16\" Spatial Display, portrait (LKG-H)",
       "LKG-H",
       2160,
       3840,
       283,
       44.72,
       -7.45,
       0,
       50,
       {11, 6, 5995, 6000},
       4,
       kGen3PortraitCells},
      {"32-gen3",
       "Looking Glass 32\" Spatial Display, landscape (LKG-L)",
       "LKG-L",
       7680,
       4320,
       280,
       75,
       -7.2,
       -0.2,
       50,
       {7, 7, 8190, 8190},
       0,
       {}},
      {"32-gen3-portrait",
       "Looking Glass 32\" Spatial Display, portrait (LKG-K)",
       "LKG-K",
       4320,
       7680,
       280,
       80.7,
       -6.3,
       -0.3,
       54,
       {11, 6, 8184, 8184},
       2,
       kGen3LandscapeCells},
  };
  std::vector<LenticularPreset> presets;
  for (const Template& t : templates) presets.push_back(make(t));
  return presets;
}

}  // namespace

const std::vector<LenticularPreset>& lenticularPresets() {
  static const std::vector<LenticularPreset> presets = build();
  return presets;
}

std::optional<LenticularCalibration> lenticularPreset(const std::string& name) {
  for (const LenticularPreset& p : lenticularPresets())
    if (p.name == name) return p.calibration;
  return std::nullopt;
}

std::string lenticularPresetDescription(const std::string& name) {
  for (const LenticularPreset& p : lenticularPresets())
    if (p.name == name) return p.description;
  return "";
}

std::string lenticularPresetNames() {
  std::string names;
  for (const LenticularPreset& p : lenticularPresets())
    names += (names.empty() ? "" : ", ") + p.name;
  return names;
}

RecognisedDevice recogniseLenticularDevice(const LenticularCalibration& c) {
  const auto samePanel = [&c](const LenticularCalibration& p) {
    return p.screenW == c.screenW && p.screenH == c.screenH;
  };
  // The serial names the product line (Looking Glass's own readers pick the quilt by it); its
  // resolution must agree, or the prefix is another product's (a Go turned landscape).
  for (const LenticularPreset& p : lenticularPresets())
    if (!c.serial.empty() && c.serial.rfind(p.serialPrefix, 0) == 0 && samePanel(p.calibration))
      return {&p, "serial " + c.serial};
  const LenticularPreset* nearest = nullptr;
  double nearestDistance = 0;
  for (const LenticularPreset& p : lenticularPresets()) {
    if (!samePanel(p.calibration) || !(std::abs(c.dpi / p.calibration.dpi - 1.0) <= 0.01)) continue;
    const double distance = std::abs(std::log(c.pitch / p.calibration.pitch));
    if (!nearest || distance < nearestDistance) nearest = &p, nearestDistance = distance;
  }
  if (!nearest) return {};
  char basis[128];
  std::snprintf(basis, sizeof basis, "%dx%d pixels at %g DPI, pitch %g", c.screenW, c.screenH,
                c.dpi, c.pitch);
  return {nearest, basis};
}

QuiltFormat derivedQuilt(int screenW, int screenH) {
  const double aspect = double(screenW) / screenH;
  QuiltFormat q;
  double best = 1e9;
  for (int views = 40; views <= 66; ++views)
    for (int columns = 1; columns <= views; ++columns) {
      if (views % columns) continue;
      const int rows = views / columns;
      // Square quilt: a tile's aspect is rows / columns. A view more or less than 48 weighs as
      // much as a 0.2% error in aspect.
      const double score =
          std::abs(std::log(double(rows) / columns / aspect)) + 0.002 * std::abs(views - 48);
      if (score < best) best = score, q.columns = columns, q.rows = rows;
    }
  const int step = std::lcm(q.columns, q.rows);
  int side = int(std::lround(q.columns * screenW / 4.0));
  side = std::clamp(side, 2048, 8192) / step * step;  // whole tiles, no padding
  if (side < 2048) side += step;
  q.width = q.height = side;
  return q;
}

void applyDeviceConventions(LenticularCalibration& c) {
  const RecognisedDevice device = recogniseLenticularDevice(c);
  c.device = device.preset ? device.preset->name : "";
  c.deviceBasis = device.basis;
  c.quilt = device.preset ? device.preset->calibration.quilt : derivedQuilt(c.screenW, c.screenH);
}

}  // namespace parallax
