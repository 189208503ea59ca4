#include "parallax/importer/up_axis.h"

namespace parallax {

const char* upAxisName(UpAxis up) {
  switch (up) {
    case UpAxis::Y:
      return "y";
    case UpAxis::Z:
      return "z";
    case UpAxis::MinusY:
      return "-y";
    case UpAxis::Auto:
      break;
  }
  return "auto";
}

bool parseUpAxis(const std::string& text, UpAxis& up) {
  for (UpAxis candidate : {UpAxis::Auto, UpAxis::Y, UpAxis::Z, UpAxis::MinusY})
    if (text == upAxisName(candidate)) return up = candidate, true;
  return false;
}

}  // namespace parallax
