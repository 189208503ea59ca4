// Triangle meshes from files: OBJ (+MTL), PLY (ASCII and binary), STL (ASCII and binary),
// glTF 2.0 (.gltf + .bin + textures, and .glb) by our own readers, and every other format
// assimp knows (.fbx, .dae, .3ds, .blend, ...) through assimp. The format is chosen by the file
// extension. docs/import.md lists the formats, the readers and what loadMeshFile adds.
#pragma once

#include <optional>
#include <string>

#include "parallax/core/transform.h"
#include "parallax/importer/up_axis.h"
#include "parallax/scene/scene.h"

namespace parallax {

inline constexpr float kDefaultCreaseDegrees = 60.0f;

// The import choices made once for every mesh of a scene (the command line's --up and
// --crease); a scene file's mesh object may override them with its `up` and `crease` keys.
struct ImportOptions {
  UpAxis up = UpAxis::Auto;
  float creaseDegrees = kDefaultCreaseDegrees;
};

struct MeshLoadOptions {
  // Applied on top of the file's own node transforms (glTF), object -> world.
  Transform worldFromFile;
  // If set, every triangle gets this material and the file's materials are ignored.
  std::optional<uint32_t> materialOverride;
  // Prefix for mesh names (the scene object's name); file names are used when empty.
  std::string name;
  // A Z-up file is turned Y-up (-90 degrees about X) before worldFromFile.
  UpAxis up = UpAxis::Auto;
  // Parts without normals in the file get angle-weighted vertex normals, smooth across edges
  // whose faces meet at up to this angle (degrees) and split across sharper ones, so a cube
  // stays faceted. 0: no normals are generated (flat shading, as before). In [0, 180].
  float creaseDegrees = kDefaultCreaseDegrees;
  // Assimp reads every format, ours too; our own readers are the default where they exist
  // (faster, docs/import.md). Forcing assimp works around a problem in one of ours.
  bool forceAssimp = false;
};

// Appends the file's triangles to `scene` as world-space meshes (one per material), and its
// materials, textures and images, and one Scene::ImportRecord saying what was done. Degenerate
// triangles are dropped with one warning per file in scene.warnings that counts them. A glTF
// file's perspective cameras go to scene.cameras, its KHR_lights_punctual lights to
// scene.lights (both moved by worldFromFile), and one line saying what was taken and ignored
// to scene.notes (docs/gltf.md). Throws InputError naming the file for a missing, empty,
// truncated or malformed file, NaN/inf vertices or indices out of range.
void loadMeshFile(const std::string& path, const MeshLoadOptions& options, Scene& scene);

// True if the extension names a mesh format that loadMeshFile reads.
bool isMeshFile(const std::string& path);

}  // namespace parallax
