// Scene files: the JSON format of docs/scene-format.md, or a bare mesh file which is framed
// automatically and lit by a default light.
#pragma once

#include <string>

#include "parallax/io/mesh_file.h"
#include "parallax/scene/scene.h"

namespace parallax {

// Loads a .json scene or a bare mesh file (see isMeshFile). Throws InputError with the file
// and the JSON pointer of the offending key: "scene.json: /objects/3/material/color: expected
// 3 numbers". Unknown keys are errors. `import` applies to every mesh file the scene loads,
// unless its object says otherwise (`up`, `crease`).
Scene loadScene(const std::string& path, const ImportOptions& import = {});

// Wraps a bare mesh file in a scene: a grey diffuse material unless the file has its own, a
// key light and ambient fill, the display placed at the mesh's centre facing +z, scaled to
// the mesh's width, and a camera framing it.
Scene sceneFromMesh(const std::string& path, const ImportOptions& import = {});

// The scene `render` drew into `renderDir`: loadScene(scenePath) (the built-in scene when
// empty) with the framing that DIR/render.json records (/framing/fit, /focus, /depth_budget),
// so that frameForDisplay (camera/framing.h) frames it as the render did, and its meshes imported
// with the record's /import_options (up, crease; docs/import.md). Without a record the scene's
// own framing and the default import options are kept.
Scene loadSceneAsRendered(const std::string& scenePath, const std::string& renderDir);

}  // namespace parallax
