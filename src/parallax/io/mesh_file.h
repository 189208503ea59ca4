// Triangle meshes from files: OBJ (+MTL), PLY (ASCII and binary), STL (ASCII and binary),
// glTF 2.0 (.gltf + .bin + textures, and .glb). The format is chosen by the file extension.
#pragma once

#include <optional>
#include <string>

#include "parallax/core/transform.h"
#include "parallax/scene/scene.h"

namespace parallax {

struct MeshLoadOptions {
  // Applied on top of the file's own node transforms (glTF), object -> world.
  Transform worldFromFile;
  // If set, every triangle gets this material and the file's materials are ignored.
  std::optional<uint32_t> materialOverride;
  // Prefix for mesh names (the scene object's name); file names are used when empty.
  std::string name;
};

// Appends the file's triangles to `scene` as world-space meshes (one per material), and its
// materials, textures and images. Degenerate triangles are dropped with one warning per file
// in scene.warnings that counts them. A glTF file's perspective cameras go to scene.cameras,
// its KHR_lights_punctual lights to scene.lights (both moved by worldFromFile), and one line
// saying what was taken and ignored to scene.notes (docs/gltf.md). Throws InputError naming the
// file for a missing, empty, truncated or malformed file, NaN/inf vertices or indices out of range.
void loadMeshFile(const std::string& path, const MeshLoadOptions& options, Scene& scene);

// True if the extension names a mesh format that loadMeshFile reads.
bool isMeshFile(const std::string& path);

}  // namespace parallax
