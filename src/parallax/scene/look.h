// How the scene's light becomes the display's (docs/look.md): an exposure in stops and a view
// transform, as Blender's Color Management sets them for a scene. Applied to each film pixel
// (the mean of its samples) by the renderer, so every picture of the scene gets it alike: the
// layers, `view`, quilts, and the ideal views that the layer solvers and the simulator compare
// with.
//   standard: x 2^exposure, clipped to [0, 1] when encoded (the default; the look of every
//             render before it);
//   filmic:   a log encoding of x 2^exposure over 16.5 stops around middle grey
//             (L = (log2(x / 0.18) + 10) / 16.5, clamped to [0, 1], as Blender's Filmic), an
//             S-curve f(L) = 1 / (1 + (k (1 - L) / L)^s) (s = 1.6, k so that middle grey keeps
//             the sRGB code 0.461 it has under standard), and the sRGB decoding of f back to
//             linear: highlights roll off to white instead of clipping, per channel (bright
//             colours desaturate toward white, as film does).
#pragma once

#include <optional>
#include <string>

#include "parallax/core/math.h"

namespace parallax {

enum class ViewTransform { Standard, Filmic };

struct Look {
  double exposureStops = 0.0;
  ViewTransform transform = ViewTransform::Standard;

  // The standard transform at exposure 0: pictures exactly as without a look.
  bool identity() const { return exposureStops == 0.0 && transform == ViewTransform::Standard; }
  // Scene radiance (linear) to display light (linear, in [0, 1] for filmic).
  Vec3f apply(const Vec3f& radiance) const;
};

// "standard" or "filmic"; nullopt for another name.
std::optional<ViewTransform> parseViewTransform(const std::string& name);
const char* viewTransformName(ViewTransform transform);

// The filmic curve on one channel (x >= 0, already exposed), for the tests.
float filmicCurve(float x);

}  // namespace parallax
