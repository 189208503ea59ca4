// Shared by the request layer's tests: the field a refusal names, and two small displays.
#pragma once

#include <functional>
#include <string>

#include "parallax/core/error.h"
#include "parallax/display/lenticular_presets.h"
#include "parallax/io/display_file.h"
#include "parallax/render/display_test_support.h"

namespace parallax::jobs {

// A barrier display file of 320x180 pixels and 9 views.
inline const std::string kSmallDisplayFile = PARALLAX_SOURCE_DIR "/displays/small.json";

// The field a request's check names, or "" when it passes.
inline std::string fieldOf(const std::function<void()>& check) {
  try {
    check();
  } catch (const RequestError& e) {
    return e.field();
  }
  return "";
}

// A 90x30 crop of the built-in barrier display: renders in milliseconds.
inline DisplayDescription smallBarrier() {
  DisplayDescription d;
  d.barrier = smallDisplaySpec(90, 30);
  return d;
}

// The Looking Glass Portrait's preset calibration.
inline DisplayDescription portrait() {
  DisplayDescription d;
  d.kind = DisplayKind::Lenticular;
  d.lenticular = *lenticularPreset("portrait");
  return d;
}

}  // namespace parallax::jobs
