// Scene files: the JSON format of docs/scene-format.md, or a bare mesh file which is framed
// automatically and lit by a default light.
#pragma once

#include <optional>
#include <string>

#include "parallax/importer/mesh_file.h"
#include "parallax/scene/scene.h"

namespace parallax {

// Choices made when a scene is loaded (the command line's scene options).
struct SceneLoadOptions {
  // --camera NAME|INDEX: one of the cameras the scene's mesh files bring (glTF), by name or by
  // index in Scene::cameras. It becomes scene.camera (`view`) and places the display (`render`)
  // so that the display is seen as the camera saw the scene (useFileCamera). Empty: the first
  // camera of a bare mesh file, none for a .json scene.
  std::string camera;
  // --focus-on NAME: an object of the scene (a glTF node's name, as Blender's outliner shows it;
  // else a scene file object's or a mesh's name) whose centre the display's zero-parallax plane
  // goes through; with a file camera, its shot's focus distance (docs/gltf.md). Empty: none.
  std::string focusOn;
  // --up, --crease: how mesh files are imported (importer/mesh_file.h, docs/import.md).
  ImportOptions import;
  // --exposure, --view-transform: the scene's look (scene/look.h, docs/look.md) instead of its
  // file's "look"; applied by jobs' scene loading to files, built-in scenes and photos alike.
  std::optional<double> exposureStops;
  std::string viewTransform;  // "standard", "filmic"; "": the scene's own
};

// Loads a .json scene or a bare mesh file (see isMeshFile). Throws InputError with the file
// and the JSON pointer of the offending key: "scene.json: /objects/3/material/color: expected
// 3 numbers". Unknown keys are errors. options.import applies to every mesh file the scene
// loads, unless its object says otherwise (`up`, `crease`). An unknown options.camera is an
// InputError naming
// --camera and listing the scene's cameras. Lights facing away from everything are warned
// about (scene/light_checks.h).
Scene loadScene(const std::string& path, const SceneLoadOptions& options = {});

// --focus-on NAME (SceneLoadOptions::focusOn): the zero-parallax plane through the centre of the
// object called `name` (a file node's name, else a mesh's or sphere's). A file camera's shot
// keeps its line of sight and takes the object's depth along it as its focus distance; any
// other placement moves its centre along its normal to that depth (focus offset 0 unless
// given). loadScene applies it; the built-in scene gets it from the caller. Throws
// RequestError("focus_on") naming the object when there is none of that name.
void focusOnObject(Scene& scene, const std::string& name);

// Wraps a bare mesh file in a scene: a grey diffuse material unless the file has its own, the
// file's lights (glTF punctual lights, emissive meshes) or else a key light and ambient fill,
// the display placed at the mesh's centre facing +z, scaled to the mesh's width, and a camera
// framing it; with a camera of the file's (the first, or options.camera), that camera's view.
Scene sceneFromMesh(const std::string& path, const SceneLoadOptions& options = {});

// Makes scene.cameras[index] the scene's camera and places the display on its line of sight:
// the display's normal points back toward the camera, its up is the camera's up, its centre is
// where the line of sight passes the content's centre depth, and its width is fitted to the
// content (DisplayPlacement::fit) unless a scene file gives one, so that a viewer in front of the
// display sees the scene from where the camera saw it. Appends which camera is used to the file's
// note.
void useFileCamera(Scene& scene, size_t index);

// The scene `render` drew into `renderDir`: loadScene(scenePath) (the built-in scene when
// empty) with the framing that DIR/render.json records (/framing/fit, /focus, /depth_budget),
// so that frameForDisplay (camera/framing.h) frames it as the render did, and its meshes imported
// with the record's /import_options (up, crease; docs/import.md). Without a record the scene's
// own framing and the default import options are kept.
Scene loadSceneAsRendered(const std::string& scenePath, const std::string& renderDir);

}  // namespace parallax
