// Checks of a loaded scene's lights that catch files exported with a light turned the wrong
// way: an emitter whose light can reach nothing in the scene (docs/gltf.md, "Lights facing
// away").
#pragma once

#include <string>
#include <vector>

#include "parallax/scene/scene.h"

namespace parallax {

// One warning for each one-sided quad or mesh light whose emitting side faces away from every
// other object (each object's bounds lie wholly behind the plane of every emitting triangle),
// and for each spot light whose cone misses every object (each object's bounding sphere lies
// wholly outside the outer cone). Conservative: it warns only when no light can reach any
// object; a light in a scene with no other object gets no warning.
std::vector<std::string> lightFacingWarnings(const Scene& scene);

}  // namespace parallax
