// The JSON scene format; docs/scene-format.md documents every key this file reads.
#include "parallax/importer/scene_file.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <filesystem>
#include <map>

#include "parallax/core/error.h"
#include "parallax/core/transform.h"
#include "parallax/importer/mesh_file.h"
#include "parallax/io/image_file.h"
#include "parallax/io/input_file.h"
#include "parallax/io/json_reader.h"
#include "parallax/scene/light_checks.h"
#include "parallax/scene/motion.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

constexpr int kFormatVersion = 1;
const Vec3f kDefaultAlbedo{0.8f};

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// The "up" used when none is given for something facing `normal`: world +y, or -z when the
// normal is (nearly) vertical, so that a floor's v axis points away from the viewer.
Vec3f defaultUp(const Vec3f& normal) {
  return std::abs(normal.y) > 0.999f ? Vec3f(0, 0, -1) : Vec3f(0, 1, 0);
}

// `up` made perpendicular to the unit `normal` (Gram-Schmidt), or nullopt if they are parallel.
std::optional<Vec3f> perpendicularUp(const Vec3f& up, const Vec3f& normal) {
  const Vec3f v = up - normal * dot(up, normal);
  if (!(length(v) > 1e-4f * length(up))) return std::nullopt;
  return normalize(v);
}

void transformMesh(TriangleMesh& mesh, const Transform& worldFromObject) {
  for (Vec3f& p : mesh.positions) p = worldFromObject.point(p);
  for (Vec3f& n : mesh.normals) n = normalize(worldFromObject.normal(n));
  // A mirroring transform turns the triangles' winding around; swap two corners so that the
  // winding agrees with the (correctly transformed) normals again.
  if (worldFromObject.swapsHandedness())
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
      std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
}

// The factor s if the linear part of `t` is s times a rotation or reflection (a similarity),
// the only transforms that keep a sphere a sphere.
std::optional<float> uniformScale(const Transform& t) {
  const Vec3f c[3] = {t.vector({1, 0, 0}), t.vector({0, 1, 0}), t.vector({0, 0, 1})};
  const float s = length(c[0]);
  constexpr float kTolerance = 1e-4f;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(length(c[i]) - s) > kTolerance * s) return std::nullopt;
    if (std::abs(dot(c[i], c[(i + 1) % 3])) > kTolerance * s * s) return std::nullopt;
  }
  return s;
}

// Extent of `bounds` along the unit direction `axis`.
float extentAlong(const Bounds3f& bounds, const Vec3f& axis) {
  const Vec3f d = bounds.diagonal();
  return std::abs(axis.x) * d.x + std::abs(axis.y) * d.y + std::abs(axis.z) * d.z;
}

// Where the display goes when the file does not say: at the centre of `bounds`, facing +z,
// its width fitted to each display so that the bounds are seen whole (fitDisplayWidth).
DisplayPlacement placeDisplay(const Bounds3f& bounds, const Vec3f& normal, const Vec3f& up) {
  DisplayPlacement display;
  display.normal = normal;
  display.up = up;
  if (bounds.empty()) return display;
  display.center = bounds.center();
  const float width = extentAlong(bounds, normalize(cross(up, normal)));
  const float largest = maxComponent(bounds.diagonal());
  display.width = width > 0 ? width : (largest > 0 ? largest : 1.0f);
  // The width actually used is fitted to each display's window (fitDisplayWidth); the extent
  // above stands in where no fit exists (a flat point, an eye outside the window).
  display.fit = bounds;
  display.content = bounds;
  return display;
}

std::string listOrNone(const std::map<std::string, int>& named, const char* what) {
  if (named.empty()) return std::string("no ") + what + " are defined";
  std::string list;
  for (const auto& [name, index] : named) list += (list.empty() ? "" : ", ") + name;
  return "defined: " + list;
}

[[noreturn]] void failUnknownName(const JsonReader& at, const std::string& name,
                                  const std::map<std::string, int>& named, const char* kind,
                                  const char* plural) {
  std::vector<std::string> names;
  for (const auto& [n, index] : named) names.push_back(n);
  const std::string suggestion = closestMatch(name, names);
  at.fail("unknown " + std::string(kind) + " '" + name + "' (" +
          (suggestion.empty() ? listOrNone(named, plural) : "did you mean '" + suggestion + "'?") +
          ")");
}

// Ranges (documented here and in docs/scene-format.md): every coordinate, size and length is
// within kMaxCoordinate scene units of zero (float keeps about 7 digits, so a scene spanning
// more than this cannot be rendered sensibly anyway), sizes above kMinSize, scale factors
// within [1/kMaxScale, kMaxScale], colours and intensities at most kMaxRadiance, rotation
// angles within +-kMaxAngle degrees and the camera's field of view in (0.01, 179) degrees.
constexpr double kMaxCoordinate = 1e6;
constexpr double kMinSize = 1e-6;
constexpr double kMaxScale = 1e6;
constexpr double kMaxRadiance = 1e9;
constexpr double kMaxAngle = 1e6;
constexpr double kMinFov = 0.01, kMaxFov = 179;

// A position or a vector in scene units: [x, y, z], each within kMaxCoordinate.
Vec3f point(const JsonReader& value) {
  const Vec3f p = value.vec3();
  for (int axis = 0; axis < 3; ++axis)
    if (!(std::abs(p[axis]) <= kMaxCoordinate))
      value.fail("coordinates must be within -1e6 to 1e6 scene units, found " + value.dump());
  return p;
}

Vec3f point(const JsonReader& object, std::string_view key, const Vec3f& fallback) {
  const auto v = object.find(key);
  return v ? point(*v) : fallback;
}

// A length or size in scene units: positive, from kMinSize to kMaxCoordinate.
float sizeValue(const JsonReader& value) {
  const float v = value.positive();
  if (!(v >= kMinSize && v <= kMaxCoordinate))
    value.fail("expected a size from 1e-6 to 1e6 scene units, found " + value.dump());
  return v;
}

// A colour, light intensity or emission: every channel from 0 to kMaxRadiance.
Vec3f radiance(const JsonReader& value) {
  const Vec3f c = value.color();
  if (!(maxComponent(c) <= kMaxRadiance))
    value.fail("expected values from 0 to 1e9, found " + value.dump());
  return c;
}

Vec3f radiance(const JsonReader& object, std::string_view key, const Vec3f& fallback) {
  const auto v = object.find(key);
  return v ? radiance(*v) : fallback;
}

// Every entry of a transform must stay finite (a product of large scales can overflow).
void requireFinite(const JsonReader& at, const Transform& t) {
  for (const Mat4* m : {&t.matrix(), &t.inverseMatrix()})
    for (const auto& row : m->m)
      for (const float v : row)
        if (!std::isfinite(v)) at.fail("the transform overflows (scales too large or too small)");
}

Transform readMatrix(const JsonReader& value) {
  const std::vector<JsonReader> items = value.elements();
  Mat4 m;
  if (items.size() == 16) {
    for (size_t i = 0; i < 16; ++i)
      m.m[i / 4][i % 4] = float(items[i].number(-kMaxScale, kMaxScale));
  } else if (items.size() == 4) {
    for (size_t row = 0; row < 4; ++row) {
      const std::vector<JsonReader> cells = items[row].elements();
      if (cells.size() != 4) items[row].fail("expected a row of 4 numbers");
      for (size_t col = 0; col < 4; ++col)
        m.m[row][col] = float(cells[col].number(-kMaxScale, kMaxScale));
    }
  } else {
    value.fail("expected 16 numbers (row-major) or 4 rows of 4 numbers");
  }
  if (m.m[3] != std::array<float, 4>{0, 0, 0, 1})
    value.fail("the last row must be [0, 0, 0, 1] (only affine transforms are allowed)");
  Mat4 inverse;
  if (!invert(m, inverse)) value.fail("singular transform (it flattens the object)");
  return {m, inverse};
}

Transform readStep(const JsonReader& step) {
  step.expectObject({"translate", "rotate", "scale", "matrix"});
  if (step.size() != 1) step.fail("a step has exactly one of translate, rotate, scale, matrix");
  const auto [kind, value] = step.members().front();
  if (kind == "translate") return Transform::translate(point(value));
  if (kind == "rotate") {
    value.expectObject({"angle", "axis"});
    return Transform::rotate(float(value["angle"].number(-kMaxAngle, kMaxAngle)),
                             value["axis"].direction());
  }
  if (kind == "scale") {
    if (!value.isNumber() && !value.isArray())
      value.fail("expected a number or 3 numbers [x, y, z], found " + value.typeName());
    const Vec3f s = value.isNumber() ? Vec3f(float(value.number())) : value.vec3();
    if (s.x == 0 || s.y == 0 || s.z == 0) value.fail("singular transform: scale by zero");
    for (int axis = 0; axis < 3; ++axis)
      if (!(std::abs(s[axis]) >= 1 / kMaxScale && std::abs(s[axis]) <= kMaxScale))
        value.fail("scale factors must be within 1e-6 to 1e6 in size, found " + value.dump());
    return Transform::scale(s);
  }
  return readMatrix(value);
}

// Either {"matrix": ...} or a list of steps. Steps apply in list order to the object: the
// first step acts on the object as written, the next on that result, so the overall
// world-from-object transform is the product of the steps in reverse order.
Transform readTransform(const JsonReader& value) {
  if (value.isObject()) {
    value.expectObject({"matrix"});
    return readMatrix(value["matrix"]);
  }
  if (!value.isArray())
    value.fail(
        "expected a list of steps like [{\"scale\": 2}, {\"translate\": [0, 1, 0]}] or "
        "{\"matrix\": [...]}");
  Transform worldFromObject;
  for (const JsonReader& step : value.elements()) {
    worldFromObject = readStep(step) * worldFromObject;
    requireFinite(step, worldFromObject);
  }
  return worldFromObject;
}

// A reflectance: a colour with every channel in [0, 1].
Vec3f reflectance(const JsonReader& value) {
  const Vec3f c = value.color();
  if (maxComponent(c) > 1) value.fail("a reflectance must be at most 1 in every channel");
  return c;
}

Vec3f positiveSize(const JsonReader& value) {
  if (value.isNumber()) return Vec3f(sizeValue(value));
  const Vec3f s = point(value);
  if (!(s.x > 0 && s.y > 0 && s.z > 0)) value.fail("every size must be positive");
  if (!(s.x >= kMinSize && s.y >= kMinSize && s.z >= kMinSize))
    value.fail("expected sizes from 1e-6 to 1e6 scene units, found " + value.dump());
  return s;
}

class SceneFileLoader {
 public:
  SceneFileLoader(const std::string& path, const ImportOptions& import)
      : path_(path), folder_(fs::path(path).parent_path()), import_(import) {}

  Scene load() {
    const JsonDocument document = JsonDocument::parseFile(path_);
    const JsonReader root = document.root();
    root.expectObject({"version", "objects", "splats", "materials", "textures", "lights", "ambient",
                       "background", "max_depth", "camera", "display", "animation", "look"});
    if (const auto version = root.find("version"))
      if (version->integer(0, INT_MAX) != kFormatVersion)
        version->fail("unsupported version " + version->dump() + " (this build reads version " +
                      std::to_string(kFormatVersion) + ")");
    scene_.source = path_;
    scene_.ambient = radiance(root, "ambient", Vec3f(0.0f));
    scene_.background = radiance(root, "background", Vec3f(0.0f));
    scene_.maxDepth = root.integer("max_depth", scene_.maxDepth, 0, 64);
    if (const auto look = root.find("look")) scene_.look = readLook(*look);
    if (const auto textures = root.find("textures"))
      for (const auto& [name, texture] : textures->members()) {
        scene_.textures.push_back(readTexture(texture));
        namedTextures_[name] = int(scene_.textures.size()) - 1;
      }
    if (const auto materials = root.find("materials"))
      for (const auto& [name, material] : materials->members()) {
        scene_.materials.push_back(readMaterial(material, name));
        namedMaterials_[name] = int(scene_.materials.size()) - 1;
      }
    if (const auto objects = root.find("objects")) {
      const auto list = objects->elements();
      for (size_t i = 0; i < list.size(); ++i) readObject(list[i], i);
    }
    if (const auto splats = root.find("splats")) {
      if (splats->isObject()) {
        addSplatFile(*splats);
      } else {
        for (const JsonReader& entry : splats->elements()) addSplatFile(entry);
      }
    }
    if (scene_.meshes.empty() && scene_.spheres.empty() && scene_.splats.empty())
      scene_.warnings.push_back(path_ + ": the scene has no objects");
    const Bounds3f objectBounds = scene_.framingBounds();  // before light quads are added
    if (const auto lights = root.find("lights"))
      for (const JsonReader& light : lights->elements()) readLight(light);
    addMeshLights();
    readDisplay(root.find("display"), objectBounds);
    if (const auto camera = root.find("camera"))
      scene_.camera = readCamera(*camera);
    else
      scene_.camera = frameScene(scene_);
    if (const auto animation = root.find("animation")) readAnimation(*animation);
    return std::move(scene_);
  }

 private:
  // "look": {"exposure": stops, "view_transform": "standard" | "filmic"} (scene/look.h).
  static Look readLook(const JsonReader& value) {
    value.expectObject({"exposure", "view_transform"});
    Look look;
    if (const auto exposure = value.find("exposure"))
      look.exposureStops = exposure->number(-20, 20);
    if (const auto transform = value.find("view_transform")) {
      const auto parsed = parseViewTransform(transform->string());
      if (!parsed) transform->fail("expected \"standard\" or \"filmic\"");
      look.transform = *parsed;
    }
    return look;
  }

  struct EmitterOptions {
    int samples = 1;
    bool twoSided = false;
  };

  std::string resolve(const std::string& file) const {
    const fs::path p(file);
    return (p.is_absolute() ? p : folder_ / p).lexically_normal().string();
  }

  int loadImage(const JsonReader& fileKey) {
    const std::string file = resolve(fileKey.string());
    if (const auto it = images_.find(file); it != images_.end()) return it->second;
    if (!fs::exists(file)) fileKey.fail("image file not found: " + file);
    try {
      scene_.images.push_back(readImage(file));
    } catch (const InputError& e) {
      fileKey.fail(e.what());
    }
    return images_[file] = int(scene_.images.size()) - 1;
  }

  Texture readTexture(const JsonReader& value) {
    const std::string type = value["type"].string();
    Texture texture;
    if (type == "checker") {
      value.expectObject({"type", "color1", "color2", "size"});
      texture.kind = Texture::Kind::Checker;
      if (const auto c = value.find("color1")) texture.color = reflectance(*c);
      if (const auto c = value.find("color2")) texture.color2 = reflectance(*c);
      if (const auto size = value.find("size")) texture.checkerSize = sizeValue(*size);
    } else if (type == "image") {
      value.expectObject({"type", "file"});
      texture.kind = Texture::Kind::Image;
      texture.image = loadImage(value["file"]);
    } else {
      value["type"].fail("unknown texture type '" + type + "' (expected checker or image)");
    }
    return texture;
  }

  // A texture reference: the name of one in "textures", or an inline texture object.
  int textureFor(const JsonReader& value) {
    if (value.isObject()) {
      scene_.textures.push_back(readTexture(value));
      return int(scene_.textures.size()) - 1;
    }
    if (!value.isString()) value.fail("expected a texture name or a texture object");
    const std::string name = value.string();
    const auto it = namedTextures_.find(name);
    if (it == namedTextures_.end())
      failUnknownName(value, name, namedTextures_, "texture", "textures");
    return it->second;
  }

  Material readMaterial(const JsonReader& value, const std::string& name) {
    value.expectObject({"color", "diffuse", "texture", "mirror", "emission", "emission_strength"});
    Material material;
    material.name = name;
    if (value.has("color") && value.has("diffuse"))
      value["diffuse"].fail("give either 'color' or 'diffuse' (they mean the same)");
    if (const auto texture = value.find("texture")) material.diffuseTexture = textureFor(*texture);
    // The texture is multiplied by the diffuse colour, which therefore defaults to white.
    material.diffuse = material.diffuseTexture >= 0 ? Vec3f(1.0f) : kDefaultAlbedo;
    if (const auto c = value.find("color")) material.diffuse = reflectance(*c);
    if (const auto c = value.find("diffuse")) material.diffuse = reflectance(*c);
    if (const auto c = value.find("mirror")) material.mirror = reflectance(*c);
    const auto strength = value.find("emission_strength");
    material.emission = radiance(value, "emission", Vec3f(strength ? 1.0f : 0.0f));
    if (strength) {
      const float factor = strength->nonNegative();
      if (!(factor <= kMaxRadiance)) strength->fail("expected a number from 0 to 1e9");
      material.emission *= factor;
      if (!(maxComponent(material.emission) <= kMaxRadiance))
        strength->fail("emission times emission_strength must stay at most 1e9");
    }
    return material;
  }

  uint32_t defaultMaterial() {
    if (!defaultMaterial_) {
      Material material;
      material.name = "default";
      material.diffuse = kDefaultAlbedo;
      scene_.materials.push_back(material);
      defaultMaterial_ = uint32_t(scene_.materials.size() - 1);
    }
    return *defaultMaterial_;
  }

  // A material reference: the name of one in "materials", or an inline material object.
  uint32_t materialFor(const JsonReader& value, const std::string& objectName) {
    if (value.isObject()) {
      scene_.materials.push_back(readMaterial(value, objectName));
      return uint32_t(scene_.materials.size() - 1);
    }
    if (!value.isString()) value.fail("expected a material name or a material object");
    const std::string name = value.string();
    const auto it = namedMaterials_.find(name);
    if (it == namedMaterials_.end())
      failUnknownName(value, name, namedMaterials_, "material", "materials");
    return uint32_t(it->second);
  }

  void readObject(const JsonReader& object, size_t index) {
    static const std::vector<std::string> common = {
        "name", "shape", "material", "transform", "light_samples", "light_two_sided"};
    static const std::map<std::string, std::vector<std::string>> shapeKeys = {
        {"sphere", {"center", "radius"}},
        {"box", {"min", "max", "size", "center"}},
        {"quad", {"corner", "edge_u", "edge_v"}},
        {"plane", {"center", "normal", "up", "size"}},
        {"mesh", {"file", "up", "crease"}}};
    std::vector<std::string> allowed = common;
    if (!object.has("shape")) {  // a misspelt "shape" is better reported as unknown key
      for (const auto& [shape, keys] : shapeKeys)
        allowed.insert(allowed.end(), keys.begin(), keys.end());
      object.expectObject(allowed);
    }
    const JsonReader shapeKey = object["shape"];
    const std::string shape = shapeKey.string();
    const auto keys = shapeKeys.find(shape);
    if (keys == shapeKeys.end()) {
      std::vector<std::string> shapes;
      for (const auto& [s, k] : shapeKeys) shapes.push_back(s);
      const std::string hint = closestMatch(shape, shapes);
      shapeKey.fail("unknown shape '" + shape + "' (" +
                    (hint.empty() ? "expected sphere, box, quad, plane or mesh"
                                  : "did you mean '" + hint + "'?") +
                    ")");
    }
    allowed.insert(allowed.end(), keys->second.begin(), keys->second.end());
    object.expectObject(allowed);

    const std::string name = object.string("name", shape + " " + std::to_string(index));
    const auto transformKey = object.find("transform");
    const Transform worldFromObject = transformKey ? readTransform(*transformKey) : Transform();
    std::optional<uint32_t> material;
    if (const auto m = object.find("material"))
      material = materialFor(*m, name);
    else if (shape != "mesh")  // meshes keep the materials of their file
      material = defaultMaterial();

    const EmitterOptions emitter{object.integer("light_samples", 1, 1, 4096),
                                 object.boolean("light_two_sided", false)};
    const size_t firstMesh = scene_.meshes.size();
    if (shape == "sphere") {
      Sphere sphere;
      sphere.name = name;
      sphere.material = *material;
      sphere.center = worldFromObject.point(point(object, "center", Vec3f(0.0f)));
      const std::optional<float> scale = uniformScale(worldFromObject);
      if (!scale)
        transformKey->fail(
            "a sphere can only be moved, rotated, mirrored and scaled uniformly; "
            "this transform scales unevenly or shears (use a mesh for ellipsoids)");
      sphere.radius = sizeValue(object["radius"]) * *scale;
      if (!isFinite(sphere.center) ||
          !(std::abs(sphere.center.x) <= kMaxCoordinate &&
            std::abs(sphere.center.y) <= kMaxCoordinate &&
            std::abs(sphere.center.z) <= kMaxCoordinate) ||
          !(sphere.radius <= kMaxCoordinate))
        object.fail("the transformed sphere lies beyond 1e6 scene units");
      if (maxComponent(scene_.materials[*material].emission) > 0)
        scene_.warnings.push_back(path_ + ": " + object.pointer() +
                                  ": emissive spheres glow "
                                  "but do not light the scene (use a mesh or a quad light)");
      scene_.spheres.push_back(sphere);
    } else if (shape == "mesh") {
      addMeshFile(object, name, worldFromObject, material);
    } else {
      addFlatShape(object, shape, name, *material);
      transformMesh(scene_.meshes.back(), worldFromObject);
    }
    for (size_t i = firstMesh; i < scene_.meshes.size(); ++i) emitters_[i] = emitter;
    if (shape == "plane") return;
    for (size_t i = firstMesh; i < scene_.meshes.size(); ++i)
      for (const Vec3f& p : scene_.meshes[i].positions) subjects_.extend(p);
    if (shape == "sphere") {
      const Sphere& sphere = scene_.spheres.back();
      subjects_.extend(sphere.center - Vec3f(sphere.radius));
      subjects_.extend(sphere.center + Vec3f(sphere.radius));
    }
  }

  void addFlatShape(const JsonReader& object, const std::string& shape, const std::string& name,
                    uint32_t material) {
    if (shape == "box") {
      Vec3f lo, hi;
      if (object.has("size")) {
        if (object.has("min") || object.has("max"))
          object["size"].fail("give either 'size' (and 'center') or 'min' and 'max'");
        const Vec3f half = positiveSize(object["size"]) * 0.5f;
        const Vec3f center = point(object, "center", Vec3f(0.0f));
        lo = center - half;
        hi = center + half;
      } else {
        if (object.has("center")) object["center"].fail("'center' goes with 'size'");
        if (!object.has("min") || !object.has("max"))
          object.fail("a box needs 'min' and 'max', or 'size'");
        lo = point(object["min"]);
        hi = point(object["max"]);
        if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
          object["max"].fail("'max' must exceed 'min' on every axis");
      }
      addBox(scene_, name, lo, hi, material);
    } else if (shape == "quad") {
      const Vec3f corner = point(object["corner"]);
      const Vec3f u = point(object["edge_u"]), v = point(object["edge_v"]);
      if (!(length(cross(u, v)) > 0))
        object.fail("zero-area quad (edge_u and edge_v are zero or parallel)");
      addQuad(scene_, name, corner, u, v, material);
    } else {  // plane: a finite square or rectangle around `center`
      const Vec3f center = point(object, "center", Vec3f(0.0f));
      const Vec3f normal = object.direction("normal", {0, 1, 0});
      const auto upKey = object.find("up");
      const std::optional<Vec3f> v =
          perpendicularUp(upKey ? upKey->direction() : defaultUp(normal), normal);
      if (!v) upKey->fail("'up' is parallel to the normal");
      const Vec3f u = cross(*v, normal);
      const JsonReader sizeKey = object["size"];
      Vec2f size;
      if (sizeKey.isNumber()) {
        size.x = size.y = sizeValue(sizeKey);
      } else {
        const auto wh = sizeKey.elements();
        if (wh.size() != 2) sizeKey.fail("expected a number or 2 numbers [width, height]");
        size = {sizeValue(wh[0]), sizeValue(wh[1])};
      }
      const Vec3f edgeU = u * size.x, edgeV = *v * size.y;
      addQuad(scene_, name, center - edgeU * 0.5f - edgeV * 0.5f, edgeU, edgeV, material);
    }
  }

  // The file `fileKey` names, relative to the scene file: a regular file, else a refusal naming
  // the key ("mesh file not found: ...", `what` being "mesh").
  std::string existingFile(const JsonReader& fileKey, const char* what) {
    const std::string file = resolve(fileKey.string());
    if (!fs::exists(file)) fileKey.fail(std::string(what) + " file not found: " + file);
    try {
      requireRegularFile(file);
    } catch (const InputError& e) {
      fileKey.fail(e.what());
    }
    return file;
  }

  void addMeshFile(const JsonReader& object, const std::string& name,
                   const Transform& worldFromObject, std::optional<uint32_t> material) {
    const JsonReader fileKey = object["file"];
    const std::string file = existingFile(fileKey, "mesh");
    if (!isMeshFile(file))
      fileKey.fail("not a mesh file this build reads (docs/import.md lists the formats): " + file);
    MeshLoadOptions options;
    options.up = import_.up;
    if (const auto up = object.find("up"); up && !parseUpAxis(up->string(), options.up))
      up->fail("expected \"auto\", \"y\", \"z\" or \"-y\", found \"" + up->string() + "\"");
    options.creaseDegrees = import_.creaseDegrees;
    if (const auto crease = object.find("crease"))
      options.creaseDegrees = float(crease->number(0, 180));
    options.worldFromFile = worldFromObject;
    options.materialOverride = material;
    options.name = name;
    const size_t firstMesh = scene_.meshes.size();
    loadMeshFile(file, options, scene_);
    for (size_t i = firstMesh; i < scene_.meshes.size(); ++i)
      if (scene_.meshes[i].material >= scene_.materials.size())
        scene_.meshes[i].material = defaultMaterial();
  }

  // A "splats" entry (docs/scene-format.md, docs/splats.md): a Gaussian splat file, placed by
  // its transform, turned from its own up axis first as a bare file is.
  void addSplatFile(const JsonReader& entry) {
    entry.expectObject({"file", "transform", "up"});
    const JsonReader fileKey = entry["file"];
    const std::string file = existingFile(fileKey, "splat");
    MeshLoadOptions options;
    options.up = import_.up;
    if (const auto up = entry.find("up"); up && !parseUpAxis(up->string(), options.up))
      up->fail("expected \"auto\", \"y\", \"z\" or \"-y\", found \"" + up->string() + "\"");
    if (const auto transform = entry.find("transform"))
      options.worldFromFile = readTransform(*transform);
    const size_t meshes = scene_.meshes.size(), sets = scene_.splats.size();
    if (lowerExtension(file) != ".ply")
      fileKey.fail("not a splat file this build reads (.ply): " + file);
    loadMeshFile(file, options, scene_);
    if (scene_.meshes.size() != meshes || scene_.splats.size() == sets)
      fileKey.fail("holds triangles, not Gaussian splats (place meshes under \"objects\"): " +
                   file);
  }

  void readLight(const JsonReader& value) {
    const JsonReader typeKey = value["type"];
    const std::string type = typeKey.string();
    Light light;
    if (type == "point") {
      value.expectObject({"type", "name", "position", "intensity"});
      light.kind = Light::Kind::Point;
      light.position = point(value["position"]);
      light.intensity = radiance(value["intensity"]);
    } else if (type == "directional") {
      value.expectObject({"type", "name", "direction", "irradiance"});
      light.kind = Light::Kind::Directional;
      light.direction = value["direction"].direction();
      light.intensity = radiance(value["irradiance"]);
    } else if (type == "quad") {
      value.expectObject(
          {"type", "name", "corner", "edge_u", "edge_v", "radiance", "samples", "two_sided"});
      light.kind = Light::Kind::Quad;
      light.corner = point(value["corner"]);
      light.edgeU = point(value["edge_u"]);
      light.edgeV = point(value["edge_v"]);
      if (!(length(cross(light.edgeU, light.edgeV)) > 0))
        value.fail("zero-area quad light (edge_u and edge_v are zero or parallel)");
      light.intensity = radiance(value["radiance"]);
      light.samples = value.integer("samples", light.samples, 1, 4096);
      light.twoSided = value.boolean("two_sided", false);
      // The light is also a visible surface: an emissive quad that cameras and mirrors see.
      Material lamp;
      lamp.name = value.string("name", "quad light " + std::to_string(scene_.lights.size()));
      lamp.diffuse = Vec3f(0.0f);
      lamp.emission = light.intensity;
      scene_.materials.push_back(lamp);
      addQuad(scene_, lamp.name, light.corner, light.edgeU, light.edgeV,
              uint32_t(scene_.materials.size() - 1));
      light.mesh = int(scene_.meshes.size()) - 1;
    } else {
      typeKey.fail("unknown light type '" + type + "' (expected point, directional or quad)");
    }
    scene_.lights.push_back(light);
  }

  // Every mesh with an emissive material that is not already a quad light's surface.
  void addMeshLights() {
    std::vector<bool> isLight(scene_.meshes.size(), false);
    for (const Light& light : scene_.lights)
      if (light.mesh >= 0) isLight[size_t(light.mesh)] = true;
    for (size_t i = 0; i < scene_.meshes.size(); ++i) {
      const Vec3f emission = scene_.materials[scene_.meshes[i].material].emission;
      if (isLight[i] || !(maxComponent(emission) > 0)) continue;
      Light light;
      light.kind = Light::Kind::Mesh;
      light.intensity = emission;
      light.mesh = int(i);
      light.samples = emitters_[i].samples;
      light.twoSided = emitters_[i].twoSided;
      scene_.lights.push_back(light);
    }
  }

  void readDisplay(const std::optional<JsonReader>& value, const Bounds3f& bounds) {
    if (value)
      value->expectObject({"center", "normal", "up", "width", "fit", "focus", "depth_budget"});
    const Vec3f normal = value ? value->direction("normal", {0, 0, 1}) : Vec3f(0, 0, 1);
    const auto upKey = value ? value->find("up") : std::nullopt;
    const std::optional<Vec3f> up =
        perpendicularUp(upKey ? upKey->direction() : defaultUp(normal), normal);
    if (!up) upKey->fail("'up' is parallel to the display normal");
    scene_.display = placeDisplay(bounds, normal, *up);
    if (!subjects_.empty()) scene_.display.content = subjects_;
    if (!value) return;
    scene_.display.center = point(*value, "center", scene_.display.center);
    if (value->find("width")) {
      scene_.display.width = sizeValue((*value)["width"]);
      scene_.display.fit.reset();
    }
    if (const auto fit = value->find("fit")) {
      const std::string mode = fit->string();
      if (mode == "window")
        scene_.display.fitMode = DisplayFit::Window;
      else if (mode == "depth")
        scene_.display.fitMode = DisplayFit::Depth;
      else if (mode == "none")
        scene_.display.fitMode = DisplayFit::None;
      else if (mode == "camera")
        scene_.display.fitMode = DisplayFit::Camera;
      else if (mode != "auto")
        fit->fail("expected window, depth, camera, none or auto, got '" + mode + "'");
    }
    scene_.display.focusMm = millimetresOrAuto(value->find("focus"), -kMaxFocusMm, kMaxFocusMm);
    scene_.display.depthBudgetMm =
        millimetresOrAuto(value->find("depth_budget"), 0, kMaxDepthBudgetMm);
  }

  // A key in display millimetres, or "auto" (unset); `lowest` itself is refused for a budget.
  static std::optional<double> millimetresOrAuto(const std::optional<JsonReader>& value,
                                                 double lowest, double highest) {
    if (!value) return std::nullopt;
    if (value->isString()) {
      if (value->string() != "auto")
        value->fail("expected a number of millimetres or \"auto\", got '" + value->string() + "'");
      return std::nullopt;
    }
    if (!value->isNumber()) value->fail("expected a number of millimetres or \"auto\"");
    const double mm = value->number();
    if (!(mm >= lowest && mm <= highest) || (lowest == 0 && !(mm > 0)))
      value->fail("expected " + std::string(lowest == 0 ? "above 0" : "from -10000") + " up to " +
                  (lowest == 0 ? "1000" : "10000") + " mm, got " + value->dump());
    return mm;
  }

  // "animation": {"camera": [keys], "display": [keys]} (docs/animation.md). A key's "time" is
  // in seconds, from 0, strictly increasing along the list.
  void readAnimation(const JsonReader& value) {
    value.expectObject({"camera", "display"});
    if (const auto keys = value.find("camera"))
      for (const JsonReader& key : keyList(*keys)) {
        CameraKey k;
        k.seconds = keyTime(key, scene_.cameraKeys);
        k.camera = readCamera(key, {"time"});
        scene_.cameraKeys.push_back(k);
      }
    if (const auto keys = value.find("display"))
      for (const JsonReader& key : keyList(*keys)) {
        key.expectObject({"time", "center", "normal", "up"});
        DisplayKey k;
        k.seconds = keyTime(key, scene_.displayKeys);
        k.center = point(key, "center", scene_.display.center);
        k.normal = key.direction("normal", scene_.display.normal);
        const auto upKey = key.find("up");
        const std::optional<Vec3f> up =
            perpendicularUp(upKey ? upKey->direction() : scene_.display.up, k.normal);
        if (!up) (upKey ? *upKey : key).fail("'up' is parallel to the display normal");
        k.up = *up;
        scene_.displayKeys.push_back(k);
      }
  }

  static std::vector<JsonReader> keyList(const JsonReader& keys) {
    std::vector<JsonReader> list = keys.elements();
    if (list.empty()) keys.fail("expected at least one key");
    return list;
  }

  template <class Key>
  static double keyTime(const JsonReader& key, const std::vector<Key>& before) {
    const JsonReader time = key["time"];
    const double seconds = time.number(0, 1e6);
    if (!before.empty() && !(seconds > before.back().seconds))
      time.fail("key times must increase: " + time.dump() + " follows " +
                std::to_string(before.back().seconds));
    return seconds;
  }

  CameraSpec readCamera(const JsonReader& value,
                        std::initializer_list<std::string_view> extraKeys = {}) const {
    std::vector<std::string> keys{"eye", "look_at", "up", "fov"};
    for (std::string_view k : extraKeys) keys.emplace_back(k);
    value.expectObject(keys);
    CameraSpec camera;
    camera.eye = point(value["eye"]);
    camera.lookAt = point(value["look_at"]);
    if (!(length(camera.lookAt - camera.eye) > 0)) value["look_at"].fail("'look_at' equals 'eye'");
    camera.up = value.direction("up", camera.up);
    if (!perpendicularUp(camera.up, normalize(camera.lookAt - camera.eye)))
      (value.has("up") ? value["up"] : value)
          .fail("'up' is parallel to the viewing direction (give an 'up' across it)");
    if (const auto fov = value.find("fov")) {
      camera.fovDegrees = float(fov->number());
      if (!(camera.fovDegrees > kMinFov && camera.fovDegrees < kMaxFov))
        fov->fail(
            "expected a vertical field of view between 0 and 180 degrees (0.01 to 179), found " +
            fov->dump());
    }
    return camera;
  }

  std::string path_;
  fs::path folder_;
  ImportOptions import_;
  Scene scene_;
  std::map<std::string, int> namedTextures_, namedMaterials_, images_;
  std::optional<uint32_t> defaultMaterial_;
  std::map<size_t, EmitterOptions> emitters_;  // by mesh index
  // The bounds of every object but planes (floors and backdrops recede on purpose): what the
  // framing measures (DisplayPlacement::content).
  Bounds3f subjects_;
};

// Every mesh with an emissive material becomes an area light (as a .json scene's do).
void addEmissiveMeshLights(Scene& scene) {
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const Vec3f emission = scene.materials[scene.meshes[i].material].emission;
    if (!(maxComponent(emission) > 0)) continue;
    Light light;
    light.kind = Light::Kind::Mesh;
    light.intensity = emission;
    light.mesh = int(i);
    scene.lights.push_back(light);
  }
}

// The cameras as "the scene's cameras: 0 'Camera', 1 'Side'" for messages.
std::string cameraList(const Scene& scene) {
  if (scene.cameras.empty()) return "the scene has no cameras";
  std::string list;
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    const NamedCamera& camera = scene.cameras[i];
    list += (list.empty() ? "" : ", ") + std::to_string(i) + " '" + camera.name + "'";
    if (!camera.nodeName.empty() && camera.nodeName != camera.name)
      list += " (node '" + camera.nodeName + "')";
  }
  return "the scene's cameras: " + list;
}

// --camera NAME|INDEX: a camera's name first (a camera may be called "1"), then its node's name
// (Blender's object name, as the outliner shows it), then an index.
size_t findCamera(const Scene& scene, const std::string& selection) {
  for (size_t i = 0; i < scene.cameras.size(); ++i)
    if (scene.cameras[i].name == selection) return i;
  for (size_t i = 0; i < scene.cameras.size(); ++i)
    if (scene.cameras[i].nodeName == selection) return i;
  int64_t index = -1;
  const bool digits =
      !selection.empty() && std::all_of(selection.begin(), selection.end(),
                                        [](unsigned char c) { return std::isdigit(c) != 0; });
  if (digits && selection.size() < 10) index = std::stoll(selection);
  if (index >= 0 && size_t(index) < scene.cameras.size()) return size_t(index);
  throw RequestError("camera", "no camera '" + selection + "' (" + cameraList(scene) + ")");
}

}  // namespace

void useFileCamera(Scene& scene, size_t index) {
  const NamedCamera& camera = scene.cameras.at(index);
  scene.camera = camera.spec;
  const Vec3f eye = camera.spec.eye;
  const Vec3f forward = normalize(camera.spec.lookAt - eye);
  const Bounds3f content = scene.display.content ? *scene.display.content : scene.framingBounds();
  // The display faces the camera: its normal is -forward, its up the camera's up.
  const Vec3f up = normalize(camera.spec.up - forward * dot(camera.spec.up, forward));
  DisplayPlacement placement = placeDisplay(content, -forward, up);
  placement.fitMode = scene.display.fitMode;
  placement.focusMm = scene.display.focusMm;
  placement.depthBudgetMm = scene.display.depthBudgetMm;
  if (!scene.display.fit) {  // a scene file's given display width stays
    placement.width = scene.display.width;
    placement.fit.reset();
  }
  if (!content.empty()) {
    // On the line of sight at the camera's focus distance: where the line of sight first meets
    // the content (as a camera's autofocus does), else at the depth of the content's centre;
    // content behind the camera (a camera inside or past the model) keeps the distance to
    // that centre.
    ShotFrame shot;
    shot.eye = eye;
    shot.yfovRadians = camera.spec.fovDegrees * (kPi / 180.0f);
    shot.aspectRatio = camera.aspectRatio;
    const Vec3f toCenter = content.center() - eye;
    float depth = dot(toCenter, forward);
    shot.focusSource = "the content's centre";
    if (const auto hit = firstHitDistance(scene, eye, forward)) {
      depth = *hit;
      shot.focusSource = "where its line of sight meets the content";
    }
    if (!(depth > 0)) depth = length(toCenter) > 0 ? length(toCenter) : 1.0f;
    shot.focusDistance = depth;
    placement.center = eye + forward * depth;
    placement.shot = shot;
    // The depth along the line of sight is what the camera's view is framed on: the look-at
    // point is the display's centre.
    scene.camera->lookAt = placement.center;
  }
  scene.display = placement;
  const std::string used = "camera " + std::to_string(index) + " '" + camera.name + "' used" +
                           (scene.cameras.size() > 1 ? " ({camera} picks another)" : "");
  if (camera.note >= 0 && size_t(camera.note) < scene.notes.size())
    scene.notes[size_t(camera.note)] += "; " + used;
  else
    scene.notes.push_back(camera.source + ": " + used);
}

Scene sceneFromMesh(const std::string& path, const SceneLoadOptions& load) {
  requireRegularFile(path);
  Scene scene;
  scene.source = path;
  MeshLoadOptions meshOptions;
  meshOptions.up = load.import.up;
  meshOptions.creaseDegrees = load.import.creaseDegrees;
  loadMeshFile(path, meshOptions, scene);
  if (scene.materials.empty()) {
    Material grey;
    grey.name = "default";
    grey.diffuse = kDefaultAlbedo;
    scene.materials.push_back(grey);
  }
  for (TriangleMesh& mesh : scene.meshes)
    if (mesh.material >= scene.materials.size()) mesh.material = 0;
  const Bounds3f bounds = scene.framingBounds();
  if (bounds.empty()) throw InputError(path, "", "the file has no triangles");
  addEmissiveMeshLights(scene);
  if (scene.lights.empty()) {
    // A key light from above, front and left: directional, so it needs no scale; the ambient
    // fill keeps the sides it misses readable. A white surface facing the key shows 0.8/pi*2.5
    // + 0.8*0.15, about 0.76. A file with lights of its own is lit by them alone.
    Light key;
    key.kind = Light::Kind::Directional;
    key.direction = normalize(Vec3f(0.4f, -1.0f, -0.6f));
    key.intensity = Vec3f(2.5f);
    scene.lights.push_back(key);
    scene.ambient = Vec3f(0.15f);
  }
  scene.background = Vec3f(0.02f);
  scene.display = placeDisplay(bounds, {0, 0, 1}, {0, 1, 0});
  scene.camera = frameScene(scene);
  if (!load.camera.empty())
    useFileCamera(scene, findCamera(scene, load.camera));
  else if (!scene.cameras.empty())
    useFileCamera(scene, 0);
  return scene;
}

// The bounds of the object called `name`: a file node's (Scene::objects), else a mesh's or a
// sphere's name; throws RequestError naming focus_on and listing some names otherwise.
static Bounds3f objectBounds(const Scene& scene, const std::string& name) {
  for (const NamedObject& object : scene.objects)
    if (object.name == name) return object.bounds;
  Bounds3f bounds;
  for (const TriangleMesh& mesh : scene.meshes)
    if (mesh.name == name)
      for (const Vec3f& p : mesh.positions) bounds.extend(p);
  for (const Sphere& sphere : scene.spheres)
    if (sphere.name == name) {
      bounds.extend(sphere.center - Vec3f(sphere.radius));
      bounds.extend(sphere.center + Vec3f(sphere.radius));
    }
  if (!bounds.empty()) return bounds;
  std::vector<std::string> names;
  for (const NamedObject& object : scene.objects) names.push_back(object.name);
  for (const TriangleMesh& mesh : scene.meshes) names.push_back(mesh.name);
  for (const Sphere& sphere : scene.spheres) names.push_back(sphere.name);
  std::string list;
  constexpr size_t kListed = 12;
  for (size_t i = 0; i < names.size() && i < kListed; ++i)
    list += (i ? ", '" : "'") + names[i] + "'";
  if (names.size() > kListed) list += ", ... (" + std::to_string(names.size()) + " in all)";
  throw RequestError("focus_on", "no object '" + name + "' (the scene's objects: " +
                                     (list.empty() ? "none" : list) + ")");
}

// --focus-on NAME: the zero-parallax plane through the object's centre. A file camera's shot
// keeps its line of sight and takes the object's depth along it as its focus distance; any
// other placement moves its centre along its normal to the object's depth, with the focus
// given there (offset 0, or --focus's).
void focusOnObject(Scene& scene, const std::string& name) {
  const Vec3f target = objectBounds(scene, name).center();
  DisplayPlacement& display = scene.display;
  if (display.shot) {
    ShotFrame& shot = *display.shot;
    const Vec3f forward = normalize(display.center - shot.eye);
    const float depth = dot(target - shot.eye, forward);
    if (!(depth > 0))
      throw RequestError("focus_on", "the object '" + name + "' is behind the camera");
    shot.focusDistance = depth;
    shot.focusSource = "--focus-on '" + name + "'";
    display.center = shot.eye + forward * depth;
    if (scene.camera) scene.camera->lookAt = display.center;
    return;
  }
  const Vec3f normal = normalize(display.normal);
  display.center = display.center + normal * dot(target - display.center, normal);
  if (!display.focusMm) display.focusMm = 0.0;
}

Scene loadScene(const std::string& path, const SceneLoadOptions& options) {
  requireRegularFile(path);
  Scene scene;
  if (lowerExtension(path) == ".json") {
    scene = SceneFileLoader(path, options.import).load();
    if (!options.camera.empty()) useFileCamera(scene, findCamera(scene, options.camera));
  } else if (isMeshFile(path)) {
    scene = sceneFromMesh(path, options);
  } else {
    throw InputError(path, "", "unknown scene format (expected a .json scene or a mesh file)");
  }
  if (!options.focusOn.empty()) focusOnObject(scene, options.focusOn);
  for (const std::string& warning : lightFacingWarnings(scene))
    scene.warnings.push_back(path + ": " + warning);
  return scene;
}

}  // namespace parallax

namespace parallax {

namespace {

// A frame of a sequence (render --frames, docs/animation.md): the scene framed over the whole
// animation as the render framed it, then posed at the frame's time, from /sequence.
void poseAsRecorded(const JsonReader& sequence, Scene& scene) {
  SceneMotion motion = sceneMotion(scene);
  if (const auto turntable = sequence.find("turntable")) {
    Turntable t;
    t.pivot = (*turntable)["pivot"].vec3();
    t.axis = (*turntable)["axis"].direction();
    t.degreesPerSecond = (*turntable)["degrees_per_second"].number();
    motion.turntable = t;
  }
  const int frames = sequence["frames"].integer(1, 1000000);
  const double fps = sequence["fps"].number(1e-9, 240);
  std::vector<double> times(static_cast<size_t>(frames));
  for (int k = 0; k < frames; ++k) times[size_t(k)] = k / fps;
  encloseMotion(scene, motion, times);
  const Scene rest = scene;
  poseScene(rest, motion, sequence["seconds"].number(0, 1e6), scene);
}

}  // namespace

Scene loadSceneAsRendered(const std::string& scenePath, const std::string& renderDir) {
  const fs::path record = fs::path(renderDir) / "render.json";
  if (renderDir.empty() || !fs::is_regular_file(record))
    return scenePath.empty() ? defaultScene() : loadScene(scenePath);
  const JsonDocument document = JsonDocument::parseFile(record.string());
  const JsonReader root = document.root();
  // The glTF camera (--camera; docs/gltf.md) and the import options (docs/import.md) the
  // render used, so that the meshes and the display are the ones it drew; records written
  // before they were recorded get the defaults, as then.
  SceneLoadOptions options;
  if (const auto camera = root.find("scene_camera"); camera && camera->isString())
    options.camera = camera->string();
  if (const auto focusOn = root.find("scene_focus_on"); focusOn && focusOn->isString())
    options.focusOn = focusOn->string();
  if (const auto imported = root.find("import_options")) {
    const JsonReader up = (*imported)["up"];
    if (!parseUpAxis(up.string(), options.import.up))
      up.fail("expected \"auto\", \"y\", \"z\" or \"-y\"");
    options.import.creaseDegrees = float((*imported)["crease"].number(0, 180));
  }
  Scene scene = scenePath.empty() ? defaultScene() : loadScene(scenePath, options);
  if (scenePath.empty() && !options.focusOn.empty()) focusOnObject(scene, options.focusOn);
  // The look the render used (--exposure, --view-transform, or the scene's own).
  if (const auto look = root.find("look")) {
    scene.look.exposureStops = (*look)["exposure"].number(-20, 20);
    const JsonReader name = (*look)["view_transform"];
    const auto transform = parseViewTransform(name.string());
    if (!transform) name.fail("expected \"standard\" or \"filmic\"");
    scene.look.transform = *transform;
  }
  if (const auto sequence = root.find("sequence")) poseAsRecorded(*sequence, scene);
  const auto framing = root.find("framing");
  if (!framing) return scene;
  DisplayPlacement& p = scene.display;
  const std::string fit = framing->string("fit", "auto");
  if (fit == "window") p.fitMode = DisplayFit::Window;
  if (fit == "depth") p.fitMode = DisplayFit::Depth;
  if (fit == "none") p.fitMode = DisplayFit::None;
  if (fit == "camera") p.fitMode = DisplayFit::Camera;
  const auto millimetres = [&framing](const char* key, std::optional<double>& value) {
    if (const auto v = framing->find(key))
      value = v->isNumber() ? std::optional(v->number()) : std::nullopt;
  };
  millimetres("focus", p.focusMm);
  millimetres("depth_budget", p.depthBudgetMm);
  return scene;
}

}  // namespace parallax
