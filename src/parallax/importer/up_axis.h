// Which file axis points up in a mesh file (docs/import.md, "Up axis"): the option, the scene
// file's key and the readers' declared axis share it.
#pragma once

#include <string>

namespace parallax {

// Auto: the format's convention: Z for STL, the FBX file's own UpAxis, -Y for Gaussian splat
// files (the COLMAP frame 3DGS captures are trained in: y down, the cameras looking along +z),
// Y otherwise (glTF is Y-up by its specification). MinusY is turned Y-up by 180 degrees about X.
enum class UpAxis { Auto, Y, Z, MinusY };
// "auto", "y", "z", "-y"; parseUpAxis returns false for anything else.
const char* upAxisName(UpAxis up);
bool parseUpAxis(const std::string& text, UpAxis& up);

}  // namespace parallax
