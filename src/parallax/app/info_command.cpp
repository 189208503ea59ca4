// `parallax info`: what a scene file holds, for people (text) and scripts (--json).
#include <cstdio>
#include <memory>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/camera/framing.h"
#include "parallax/io/json_writer.h"

namespace parallax::app {

namespace {

const char* lightKindName(Light::Kind kind) {
  switch (kind) {
    case Light::Kind::Point:
      return "point";
    case Light::Kind::Directional:
      return "directional";
    case Light::Kind::Quad:
      return "quad";
    case Light::Kind::Mesh:
      return "mesh";
    case Light::Kind::Spot:
      return "spot";
  }
  return "?";
}

// The scene framed for the built-in display as `render` frames it (camera/framing.h).
Framing builtInFraming(const Scene& scene) {
  return frameForDisplay(scene, designDisplay(defaultDisplaySpec()));
}

// The scene's display width, fitted to the built-in display when the scene does not fix it.
float builtInDisplayWidth(const Scene& scene) {
  return builtInFraming(scene).placement.width;
}

void printJson(const Scene& scene) {
  JsonWriter json;
  json.set("/source", scene.source);
  json.set("/triangles", uint64_t(scene.triangleCount()));
  json.set("/spheres", uint64_t(scene.spheres.size()));
  json.set("/gaussians", uint64_t(scene.splatCount()));
  const Bounds3f b = scene.bounds();
  json.set("/bounds/min", b.empty() ? Vec3f(0.0f) : b.lo);
  json.set("/bounds/max", b.empty() ? Vec3f(0.0f) : b.hi);
  json.setEmptyArray("/objects");
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const std::string at = "/objects/" + std::to_string(i);
    json.set(at + "/name", scene.meshes[i].name);
    json.set(at + "/type", "mesh");
    json.set(at + "/triangles", uint64_t(scene.meshes[i].triangleCount()));
    json.set(at + "/material", scene.materials[scene.meshes[i].material].name);
  }
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const std::string at = "/objects/" + std::to_string(scene.meshes.size() + i);
    json.set(at + "/name", scene.spheres[i].name);
    json.set(at + "/type", "sphere");
    json.set(at + "/material", scene.materials[scene.spheres[i].material].name);
  }
  json.setEmptyArray("/materials");
  for (size_t i = 0; i < scene.materials.size(); ++i)
    json.set("/materials/" + std::to_string(i), scene.materials[i].name);
  json.setEmptyArray("/lights");
  for (size_t i = 0; i < scene.lights.size(); ++i)
    json.set("/lights/" + std::to_string(i) + "/type", lightKindName(scene.lights[i].kind));
  // The cameras of glTF files, for --camera NAME|INDEX (docs/gltf.md).
  json.setEmptyArray("/cameras");
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    const std::string at = "/cameras/" + std::to_string(i);
    json.set(at + "/name", scene.cameras[i].name);
    json.set(at + "/node", scene.cameras[i].nodeName);
    json.set(at + "/eye", scene.cameras[i].spec.eye);
    json.set(at + "/fov", double(scene.cameras[i].spec.fovDegrees));
  }
  // The files' named nodes, for --focus-on NAME.
  json.setEmptyArray("/nodes");
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const std::string at = "/nodes/" + std::to_string(i);
    json.set(at + "/name", scene.objects[i].name);
    json.set(at + "/min", scene.objects[i].bounds.lo);
    json.set(at + "/max", scene.objects[i].bounds.hi);
  }
  json.set("/notes", scene.notes);
  json.set("/display/center", scene.display.center);
  json.set("/display/normal", scene.display.normal);
  json.set("/display/up", scene.display.up);
  json.set("/display/width", double(builtInDisplayWidth(scene)));
  json.set("/display/fitted", scene.display.fit.has_value());
  const Framing f = builtInFraming(scene);
  setFramingFigures(json, "/depth", f);
  json.set("/warnings", scene.warnings);
  json.setEmptyArray("/import");  // what loading each mesh file did (docs/import.md)
  for (size_t i = 0; i < scene.imports.size(); ++i) {
    const std::string at = "/import/" + std::to_string(i);
    json.set(at + "/file", scene.imports[i].file);
    json.set(at + "/reader", scene.imports[i].reader);
    json.set(at + "/up", scene.imports[i].up);
    json.set(at + "/normals", scene.imports[i].normals);
    json.set(at + "/triangles", uint64_t(scene.imports[i].triangles));
    json.set(at + "/splats", uint64_t(scene.imports[i].splats));
  }
  // Gaussian splat sets (docs/splats.md): what each file holds.
  json.setEmptyArray("/splats");
  for (size_t i = 0; i < scene.splats.size(); ++i) {
    const std::string at = "/splats/" + std::to_string(i);
    json.set(at + "/file", scene.splats[i].name);
    json.set(at + "/gaussians", uint64_t(scene.splats[i].cloud.size()));
    json.set(at + "/sh_degree", int64_t(scene.splats[i].cloud.shDegree));
  }
  std::printf("%s\n", json.dump().c_str());
}

void printText(const Scene& scene) {
  std::printf("scene     %s\n", scene.source.c_str());
  std::printf("triangles %zu in %zu meshes, %zu spheres\n", scene.triangleCount(),
              scene.meshes.size(), scene.spheres.size());
  const Bounds3f b = scene.bounds();
  if (!b.empty())
    std::printf("bounds    (%g, %g, %g) to (%g, %g, %g)\n", b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y,
                b.hi.z);
  std::printf("objects:\n");
  for (const auto& m : scene.meshes)
    std::printf("  %-28s mesh, %zu triangles, material %s\n", m.name.c_str(), m.triangleCount(),
                scene.materials[m.material].name.c_str());
  for (const auto& s : scene.spheres)
    std::printf("  %-28s sphere r=%g, material %s\n", s.name.c_str(), s.radius,
                scene.materials[s.material].name.c_str());
  for (const SplatSet& set : scene.splats)
    std::printf("  %-28s Gaussian splats: %zu, spherical harmonics of degree %d\n",
                set.name.c_str(), set.cloud.size(), set.cloud.shDegree);
  std::printf("materials %zu, textures %zu, images %zu\n", scene.materials.size(),
              scene.textures.size(), scene.images.size());
  std::printf("lights:\n");
  for (const auto& l : scene.lights) std::printf("  %s\n", lightKindName(l.kind));
  if (!scene.cameras.empty()) std::printf("cameras (--camera NAME|INDEX):\n");
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    const NamedCamera& c = scene.cameras[i];
    const std::string node =
        c.nodeName.empty() || c.nodeName == c.name ? "" : " (node '" + c.nodeName + "')";
    std::printf("  %zu '%s'%s at (%g, %g, %g), vertical fov %g degrees\n", i, c.name.c_str(),
                node.c_str(), c.spec.eye.x, c.spec.eye.y, c.spec.eye.z, c.spec.fovDegrees);
  }
  if (!scene.objects.empty()) std::printf("nodes (--focus-on NAME):\n");
  for (const NamedObject& o : scene.objects) {
    const Vec3f c = o.bounds.center();
    std::printf("  %-28s centre (%g, %g, %g)\n", o.name.c_str(), c.x, c.y, c.z);
  }
  for (const auto& n : scene.notes) std::printf("note: %s\n", n.c_str());
  const auto& d = scene.display;
  std::printf("display   centre (%g, %g, %g), normal (%g, %g, %g), width %g%s\n", d.center.x,
              d.center.y, d.center.z, d.normal.x, d.normal.y, d.normal.z,
              builtInDisplayWidth(scene),
              d.fit ? " (fitted to the built-in display's window)" : "");
  const Framing f = builtInFraming(scene);
  std::printf("%s\n", depthSummary(f).c_str());
  const std::string depthWarningLine = depthWarning(f);
  if (!depthWarningLine.empty()) std::printf("warning: %s\n", depthWarningLine.c_str());
  for (const auto& w : scene.warnings) std::printf("warning: %s\n", w.c_str());
}

}  // namespace

void registerInfoCommand(Command& cli) {
  struct Options {
    std::string scene;
    bool json = false;
    SceneLoadOptions load;
  };
  auto options = std::make_shared<Options>();
  Command* cmd = cli.addSubcommand("info", "Print what a scene holds");
  cmd->addOption("scene", options->scene, "Scene or mesh file; the built-in scene if omitted");
  cmd->addFlag("--json", options->json, "Print one JSON object");
  addImportOptions(*cmd);
  cmd->addOption("--camera", options->load.camera,
                 "Frame the display as this glTF camera (name, node name or index) does")
      ->typeName("NAME|INDEX");
  cmd->addOption("--focus-on", options->load.focusOn,
                 "Put the zero-parallax plane through this object (a node's or mesh's name)")
      ->typeName("NAME");
  cmd->callback([options] {
    const Scene scene = loadSceneOrDefault(options->scene, options->load);
    options->json ? printJson(scene) : printText(scene);
  });
}

}  // namespace parallax::app
