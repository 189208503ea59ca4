// glTF 2.0 (.gltf with its buffers and images, or .glb) through tinygltf, which parses the
// JSON, loads buffers and decodes images. We walk the node tree of the scene ourselves
// (glTF 2.0 specification, "Transformations": a node's matrix, or T * R * S, applies to its
// children too), expanding a mesh once per node that uses it, and read accessors with our own
// bounds checks (specification, "Accessors") since the file may be malformed. Cameras and
// KHR_lights_punctual lights come from the same walk, with their node's world transform;
// vertex colours from COLOR_0. What the file has that we do not use is listed in the file's
// note (docs/gltf.md).
#include <tiny_gltf.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "parallax/importer/mesh_readers.h"
#include "parallax/io/image_file.h"
#include "parallax/io/input_file.h"

namespace parallax::meshio {
namespace {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

constexpr size_t kMaxNodeDepth = 1000;
constexpr size_t kMaxNodeInstances = 1000000;
// Node transforms keep to the scene file's ranges (importer/scene_file.cpp, docs/scene-format.md):
// translations and matrix entries within 1e6 scene units, scale factors within 1e-6 to 1e6
// in size (or 0, which hides a node), and so does a node's world position composed through
// its parents. Float keeps about 7 digits; a file placing a mesh at 1e30 cannot be rendered
// sensibly with anything else in view.
constexpr double kMaxCoordinate = 1e6;
constexpr double kMaxScale = 1e6;

// KHR_lights_punctual gives point and spot intensities in candela (lm/sr) and directional
// ones in lux (lm/m^2); our lights are radiometric (W/sr, W/m^2). Dividing by 683 lm/W (the
// luminous efficacy at 555 nm, the constant Blender's exporter multiplies by in its default
// "Standard" lighting mode) gives back the watts Blender's lamps have (docs/gltf.md, "Units").
constexpr double kLumensPerWatt = 683.0;

// Our image loader (tinygltf::TinyGLTF::SetImageLoader): checks that an image's buffer view
// lies inside its buffer before reading it, and decodes through decodeImage, which refuses
// absurd sizes from the header. The decoded images are kept here by glTF image index.
struct ImageLoader {
  const tinygltf::Model* model = nullptr;  // buffers and buffer views are parsed before images
  std::map<int, Image> decoded;
  std::string problem;  // an InputError message to report as it is

  static bool load(tinygltf::Image* image, const int index, std::string* err, std::string*, int,
                   int, const unsigned char* bytes, int size, void* user) {
    auto& self = *static_cast<ImageLoader*>(user);
    const std::string where = "image " + std::to_string(index);
    const auto refuse = [&](const std::string& message) {
      self.problem = where + ": " + message;
      if (err) *err += self.problem + "\n";
      return false;
    };
    if (image->bufferView >= 0) {
      const auto& views = self.model->bufferViews;
      if (size_t(image->bufferView) >= views.size())
        return refuse("its buffer view does not exist");
      const tinygltf::BufferView& view = views[size_t(image->bufferView)];
      if (view.buffer < 0 || size_t(view.buffer) >= self.model->buffers.size())
        return refuse("its buffer view has no valid buffer");
      const size_t available = self.model->buffers[size_t(view.buffer)].data.size();
      if (view.byteOffset > available || view.byteLength > available - view.byteOffset)
        return refuse("its buffer view (" + std::to_string(view.byteLength) + " bytes at " +
                      std::to_string(view.byteOffset) + ") extends past the end of its buffer (" +
                      std::to_string(available) + " bytes; truncated?)");
    }
    if (!bytes || size <= 0) return refuse("no image data");
    try {
      Image decoded =
          decodeImage(std::string_view(reinterpret_cast<const char*>(bytes), size_t(size)), where);
      image->width = decoded.width();
      image->height = decoded.height();
      image->component = 3;
      image->bits = 8;
      self.decoded[index] = std::move(decoded);
    } catch (const InputError& e) {
      // decodeImage names `where` as its file; keep only the message after it.
      const std::string what = e.what();
      return refuse(what.substr(std::min(what.size(), where.size() + 2)));
    }
    return true;
  }
};

// tinygltf's file reading for buffers and images given by URI, through the same gate as
// every other input (a FIFO or a device would hang or never end).
bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& file,
                   void*) {
  try {
    const std::string bytes = readInputFile(file);
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const InputError& e) {
    if (err) *err += std::string(e.what()) + "\n";
    return false;
  }
}

// Extensions in extensionsRequired that we honour (or that need nothing from us).
bool isSupportedExtension(const std::string& name) {
  return name == "KHR_materials_emissive_strength" || name == "KHR_mesh_quantization" ||
         name == "KHR_lights_punctual";
}

// "1 camera", "3 cameras".
std::string count(size_t n, const std::string& what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

// A point and a direction through a node's world matrix (row-major, affine).
Vec3f transformPoint(const Mat4& m, const Vec3f& p) {
  Vec3f out;
  for (int r = 0; r < 3; ++r)
    out[r] = m.m[r][0] * p.x + m.m[r][1] * p.y + m.m[r][2] * p.z + m.m[r][3];
  return out;
}
Vec3f transformVector(const Mat4& m, const Vec3f& v) {
  Vec3f out;
  for (int r = 0; r < 3; ++r) out[r] = m.m[r][0] * v.x + m.m[r][1] * v.y + m.m[r][2] * v.z;
  return out;
}

// "node 3 ('Cube')": a node for messages.
std::string nodeName(const tinygltf::Model& model, int index) {
  const std::string& name = model.nodes[size_t(index)].name;
  return "node " + std::to_string(index) + (name.empty() ? "" : " ('" + name + "')");
}

// The problem with a node's own transform (kMaxCoordinate, kMaxScale), or "".
std::string transformProblem(const tinygltf::Node& node) {
  for (const double t : node.translation)
    if (!(std::abs(t) <= kMaxCoordinate))
      return "translation " + numberText(t) + " is beyond 1e6 scene units";
  for (const double s : node.scale)
    if (s != 0 && !(std::abs(s) >= 1 / kMaxScale && std::abs(s) <= kMaxScale))
      return "scale " + numberText(s) + " is not within 1e-6 to 1e6 in size (nor 0)";
  for (const double r : node.rotation)
    if (!std::isfinite(r)) return "rotation " + numberText(r) + " is not finite";
  for (const double m : node.matrix)
    if (!(std::abs(m) <= kMaxScale))
      return "matrix entry " + numberText(m) + " is beyond 1e6 in size";
  return "";
}

// A glTF matrix is column-major; Mat4 is row-major.
Mat4 nodeMatrix(const tinygltf::Node& node) {
  Mat4 m = Mat4::identity();
  if (node.matrix.size() == 16) {
    for (int row = 0; row < 4; ++row)
      for (int col = 0; col < 4; ++col) m.m[row][col] = float(node.matrix[size_t(col * 4 + row)]);
    return m;
  }
  // T * R * S, with R from the unit quaternion (x, y, z, w).
  double x = 0, y = 0, z = 0, w = 1;
  if (node.rotation.size() == 4) {
    x = node.rotation[0], y = node.rotation[1], z = node.rotation[2], w = node.rotation[3];
    const double norm = std::sqrt(x * x + y * y + z * z + w * w);
    if (norm > 0) x /= norm, y /= norm, z /= norm, w /= norm;
  }
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                          {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                          {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      const double s = node.scale.size() == 3 ? node.scale[size_t(col)] : 1.0;
      m.m[row][col] = float(r[row][col] * s);
    }
    if (node.translation.size() == 3) m.m[row][3] = float(node.translation[size_t(row)]);
  }
  return m;
}

class GltfReader {
 public:
  GltfReader(const std::string& path, const tinygltf::Model& model, std::map<int, Image>& images)
      : path_(path), model_(model), decodedImages_(images) {}

  FileContents read() {
    if (model_.asset.version.empty() || model_.asset.version[0] != '2')
      fail(path_, "glTF version '" + model_.asset.version + "' is not supported (only 2.x)");
    for (const std::string& name : model_.extensionsRequired)
      if (!isSupportedExtension(name)) fail(path_, "requires the unsupported extension " + name);
    readMaterials();
    for (size_t n = 0; n < model_.nodes.size(); ++n)
      if (const std::string problem = transformProblem(model_.nodes[n]); !problem.empty())
        fail(path_, nodeName(model_, int(n)) + ": " + problem);
    onPath_.assign(model_.nodes.size(), false);
    for (int root : rootNodes()) visitTree(root);
    readAnimations();
    if (skippedPrimitives_ > 0)
      contents_.warnings.push_back("skipped " + std::to_string(skippedPrimitives_) +
                                   " point or line primitives");
    contents_.note = note();
    return std::move(contents_);
  }

 private:
  struct AccessorView {
    const unsigned char* data = nullptr;
    size_t stride = 0, count = 0;
    int componentType = 0, componentSize = 0, components = 0;
    bool normalized = false;
  };

  std::vector<int> rootNodes() {
    const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (size_t(sceneIndex) < model_.scenes.size()) return model_.scenes[size_t(sceneIndex)].nodes;
    if (model_.defaultScene >= 0)
      contents_.warnings.push_back("the default scene " + std::to_string(model_.defaultScene) +
                                   " does not exist; using every root node");
    // No usable scene: every node that is nobody's child.
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes)
      for (int child : node.children)
        if (child >= 0 && size_t(child) < isChild.size()) isChild[size_t(child)] = true;
    std::vector<int> roots;
    for (size_t i = 0; i < isChild.size(); ++i)
      if (!isChild[i]) roots.push_back(int(i));
    return roots;
  }

  // Walks the tree under `root` depth first, without recursion (a file may chain thousands of
  // nodes), refusing a node that is its own ancestor, chains deeper than kMaxNodeDepth and
  // trees that expand (through shared children) to more than kMaxNodeInstances nodes.
  void visitTree(int root) {
    struct Frame {
      int node;
      Mat4 fileFromNode;
      size_t nextChild;
    };
    std::vector<Frame> stack;
    const auto enter = [&](int nodeIndex, const Mat4& fileFromParent) {
      if (nodeIndex < 0 || size_t(nodeIndex) >= model_.nodes.size())
        fail(path_, "node index " + std::to_string(nodeIndex) + " does not exist");
      if (onPath_[size_t(nodeIndex)])
        fail(path_, "node " + std::to_string(nodeIndex) + " is its own ancestor");
      if (stack.size() >= kMaxNodeDepth)
        fail(path_, "the node tree is more than " + std::to_string(kMaxNodeDepth) +
                        " levels deep (at node " + std::to_string(nodeIndex) + ")");
      if (++nodeInstances_ > kMaxNodeInstances)
        fail(path_, "the node tree expands to more than " + std::to_string(kMaxNodeInstances) +
                        " node instances (shared children)");
      onPath_[size_t(nodeIndex)] = true;
      const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
      const Mat4 fileFromNode = fileFromParent * nodeMatrix(node);
      for (int row = 0; row < 3; ++row)
        if (!(std::abs(fileFromNode.m[row][3]) <= kMaxCoordinate))
          fail(path_, nodeName(model_, nodeIndex) +
                          ": its position composed through its parents lies beyond 1e6 scene "
                          "units");
      if (node.mesh >= 0) {
        namedPath_.clear();  // this node's name, then its named ancestors'
        if (!node.name.empty()) namedPath_.push_back(node.name);
        for (auto frame = stack.rbegin(); frame != stack.rend(); ++frame)
          if (const std::string& name = model_.nodes[size_t(frame->node)].name; !name.empty())
            namedPath_.push_back(name);
        addMesh(node.mesh, fileFromNode, nodeIndex);
      }
      if (node.camera >= 0) addCamera(node, nodeIndex, fileFromNode);
      if (const auto light = node.extensions.find("KHR_lights_punctual");
          light != node.extensions.end())
        addLight(light->second, nodeIndex, fileFromNode);
      stack.push_back({nodeIndex, fileFromNode, 0});
    };
    enter(root, Mat4::identity());
    while (!stack.empty()) {
      Frame& top = stack.back();
      const std::vector<int>& children = model_.nodes[size_t(top.node)].children;
      if (top.nextChild < children.size()) {
        const int child = children[top.nextChild++];
        const Mat4 fileFromParent = top.fileFromNode;  // `top` may move when the stack grows
        enter(child, fileFromParent);
      } else {
        onPath_[size_t(top.node)] = false;
        stack.pop_back();
      }
    }
  }

  // A perspective camera looks down its node's -Z with +Y up (specification, "Cameras");
  // orthographic cameras are counted for the note and otherwise ignored.
  void addCamera(const tinygltf::Node& node, int nodeIndex, const Mat4& fileFromNode) {
    const std::string where =
        "node " + std::to_string(nodeIndex) + ": camera " + std::to_string(node.camera);
    if (size_t(node.camera) >= model_.cameras.size()) fail(path_, where + " does not exist");
    const tinygltf::Camera& source = model_.cameras[size_t(node.camera)];
    if (source.type == "orthographic") {
      ++orthographicCameras_;
      return;
    }
    if (source.type != "perspective")
      fail(path_, where + ": unknown camera type '" + source.type + "'");
    const tinygltf::PerspectiveCamera& p = source.perspective;
    // The specification requires 0 < yfov; a view needs it below 180 degrees too.
    if (!(p.yfov > 0 && p.yfov < kPi))
      fail(path_, where + ": yfov " + std::to_string(p.yfov) +
                      " is not an angle between 0 and pi radians");
    FileCamera camera;
    camera.name = !source.name.empty() ? source.name
                  : !node.name.empty() ? node.name
                                       : "camera " + std::to_string(contents_.cameras.size());
    camera.nodeName = node.name;
    camera.eye = transformPoint(fileFromNode, Vec3f(0.0f));
    camera.forward = transformVector(fileFromNode, {0, 0, -1});
    camera.up = transformVector(fileFromNode, {0, 1, 0});
    camera.yfov = float(p.yfov);
    camera.aspectRatio =
        std::isfinite(p.aspectRatio) && p.aspectRatio > 0 ? float(p.aspectRatio) : 0;
    camera.znear = std::isfinite(p.znear) && p.znear > 0 ? float(p.znear) : 0;
    const bool usable = isFinite(camera.eye) && length(camera.forward) > 0 &&
                        length(cross(camera.forward, camera.up)) > 0 &&
                        std::isfinite(length(camera.forward)) && std::isfinite(length(camera.up));
    if (!usable) {
      contents_.warnings.push_back(where + " ('" + camera.name +
                                   "'): its node's transform is singular; ignoring the camera");
      return;
    }
    contents_.cameras.push_back(std::move(camera));
  }

  // KHR_lights_punctual: a light shines down its node's -Z from the node's origin. Colour
  // times intensity, divided by kLumensPerWatt, is our W/sr (point, spot) or W/m^2
  // (directional); `range` is ignored (our lights fall off with 1/r^2 forever).
  void addLight(const tinygltf::Value& extension, int nodeIndex, const Mat4& fileFromNode) {
    const std::string where = "node " + std::to_string(nodeIndex) + ": KHR_lights_punctual";
    if (!extension.IsObject() || !extension.Has("light") || !extension.Get("light").IsNumber())
      fail(path_, where + ": expected {\"light\": INDEX}");
    const double index = extension.Get("light").GetNumberAsDouble();
    if (!(index >= 0 && index < double(model_.lights.size())) || index != std::floor(index))
      fail(path_, where + ": light " + (std::ostringstream() << index).str() + " does not exist (" +
                      count(model_.lights.size(), "light") + ")");
    const tinygltf::Light& source = model_.lights[size_t(index)];
    const std::string what = where + ": light " + std::to_string(size_t(index));
    Vec3f color(1.0f);
    if (source.color.size() == 3)
      color = {float(source.color[0]), float(source.color[1]), float(source.color[2])};
    else if (!source.color.empty())
      fail(path_, what + ": 'color' needs 3 numbers");
    if (!isFinite(color) || color.x < 0 || color.y < 0 || color.z < 0)
      fail(path_, what + ": 'color' must be finite and not negative");
    if (!std::isfinite(source.intensity) || source.intensity < 0)
      fail(path_, what + ": 'intensity' must be finite and not negative");
    FileLight light;
    light.light.intensity = color * float(source.intensity / kLumensPerWatt);
    light.light.position = transformPoint(fileFromNode, Vec3f(0.0f));
    const Vec3f axis = transformVector(fileFromNode, {0, 0, -1});
    if (source.type == "point") {
      light.light.kind = Light::Kind::Point;
    } else if (source.type == "directional" || source.type == "spot") {
      light.light.kind = source.type == "spot" ? Light::Kind::Spot : Light::Kind::Directional;
      if (!(length(axis) > 0) || !std::isfinite(length(axis))) {
        contents_.warnings.push_back(what + ": its node's transform is singular; ignoring it");
        return;
      }
      light.light.direction = normalize(axis);
    } else {
      fail(path_, what + ": unknown light type '" + source.type + "'");
    }
    if (source.type == "spot") {
      // The extension requires 0 <= inner < outer <= pi / 2.
      const double inner = source.spot.innerConeAngle, outer = source.spot.outerConeAngle;
      if (!(inner >= 0 && inner < outer && outer <= kPi / 2 + 1e-6))
        fail(path_, what +
                        ": spot cone angles must satisfy 0 <= innerConeAngle < "
                        "outerConeAngle <= pi/2 (got " +
                        std::to_string(inner) + " and " + std::to_string(outer) + ")");
      light.light.innerCone = float(inner);
      light.light.outerCone = float(outer);
    }
    if (!isFinite(light.light.position)) {
      contents_.warnings.push_back(what + ": its position is not finite; ignoring it");
      return;
    }
    if (source.range > 0) ++rangedLights_;
    contents_.lights.push_back(std::move(light));
  }

  // "glTF: took 2 meshes, 1 camera, 1 light, vertex colours; ignored: ...": only what the
  // file has.
  std::string note() const {
    std::vector<std::string> taken, ignored;
    taken.push_back(std::to_string(meshesUsed_.size()) +
                    (meshesUsed_.size() == 1 ? " mesh" : " meshes"));
    if (!contents_.cameras.empty()) taken.push_back(count(contents_.cameras.size(), "camera"));
    if (!contents_.lights.empty()) taken.push_back(count(contents_.lights.size(), "light"));
    if (coloredPrimitives_ > 0) taken.push_back("vertex colours (COLOR_0)");
    if (!model_.animations.empty())
      taken.push_back(count(model_.animations.size(), "animation") + " (played by {frames})");

    bool metallic = false, normalMaps = false, occlusion = false, emissiveMaps = false,
         alpha = false;
    std::set<std::string> materialExtensions;
    for (const tinygltf::Material& m : model_.materials) {
      const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
      metallic |= pbr.metallicFactor != 1.0 || pbr.roughnessFactor != 1.0 ||
                  pbr.metallicRoughnessTexture.index >= 0;
      normalMaps |= m.normalTexture.index >= 0;
      occlusion |= m.occlusionTexture.index >= 0;
      emissiveMaps |= m.emissiveTexture.index >= 0;
      alpha |= (!m.alphaMode.empty() && m.alphaMode != "OPAQUE") ||
               (pbr.baseColorFactor.size() == 4 && pbr.baseColorFactor[3] < 1.0);
      for (const auto& [name, value] : m.extensions)
        if (name != "KHR_materials_emissive_strength") materialExtensions.insert(name);
    }
    if (metallic) ignored.push_back("metallic/roughness (base colour only)");
    if (normalMaps) ignored.push_back("normal maps");
    if (occlusion) ignored.push_back("occlusion maps");
    if (emissiveMaps) ignored.push_back("emissive textures (the factor is used)");
    if (alpha) ignored.push_back("alpha (BLEND/MASK, base colour alpha)");
    if (!materialExtensions.empty())
      ignored.push_back("material extensions (" +
                        joined({materialExtensions.begin(), materialExtensions.end()}) + ")");
    if (!model_.samplers.empty())
      ignored.push_back("texture samplers (wrap and filter: we repeat and filter bilinearly)");
    if (!model_.skins.empty()) ignored.push_back(count(model_.skins.size(), "skin"));
    if (morphTargets_) ignored.push_back("morph targets");
    if (orthographicCameras_ > 0)
      ignored.push_back(count(orthographicCameras_, "orthographic camera"));
    if (rangedLights_ > 0)
      ignored.push_back("the range of " + count(rangedLights_, "light") +
                        " (ours fall off with 1/r^2 without a cut-off)");
    std::vector<std::string> extensions;
    for (const std::string& name : model_.extensionsUsed)
      if (!isSupportedExtension(name) && name.rfind("KHR_materials_", 0) != 0)
        extensions.push_back(name);
    if (!extensions.empty()) ignored.push_back("extensions " + joined(extensions));
    return "glTF: took " + joined(taken) + (ignored.empty() ? "" : "; ignored: " + joined(ignored));
  }

  void addMesh(int meshIndex, const Mat4& fileFromNode, int nodeIndex) {
    if (size_t(meshIndex) >= model_.meshes.size())
      fail(path_, "mesh index " + std::to_string(meshIndex) + " does not exist");
    meshesUsed_.insert(meshIndex);
    const tinygltf::Mesh& mesh = model_.meshes[size_t(meshIndex)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string context =
          "mesh " + (mesh.name.empty() ? std::to_string(meshIndex) : "'" + mesh.name + "'") +
          " primitive " + std::to_string(p);
      FilePart part = readPrimitive(mesh.primitives[p], context);
      if (part.indices.empty()) continue;
      try {
        part.fileFromPart = Transform(fileFromNode);
      } catch (const std::invalid_argument&) {
        // A zero scale (used to hide nodes) flattens every triangle.
        contents_.droppedDegenerate += part.indices.size() / 3;
        continue;
      }
      part.node = nodeIndex;  // kept only if the node moves (readAnimations)
      part.nodeNames = namedPath_;
      contents_.parts.push_back(std::move(part));
    }
  }

  // glTF node animation (specification, "Animations"): every animation's translation,
  // rotation and scale channels play together (an exporter writes one animation per object
  // or action; where two drive one node's property the first wins). Morph-target weights are
  // noted and ignored; CUBICSPLINE keys are played as LINEAR through their values.
  void readAnimations() {
    const auto dropNodes = [this] {
      for (FilePart& part : contents_.parts) part.node = -1;
    };
    if (model_.animations.empty()) return dropNodes();
    NodeAnimation& out = contents_.nodeAnimation;
    out.nodes.resize(model_.nodes.size());
    std::vector<int> parents(model_.nodes.size(), 0);
    for (size_t n = 0; n < model_.nodes.size(); ++n) {
      const tinygltf::Node& node = model_.nodes[n];
      AnimatedNode& a = out.nodes[n];
      if (node.matrix.size() == 16) a.matrix = nodeMatrix(node);
      if (node.translation.size() == 3)
        a.translation = Vec3f(float(node.translation[0]), float(node.translation[1]),
                              float(node.translation[2]));
      if (node.scale.size() == 3)
        a.scale = Vec3f(float(node.scale[0]), float(node.scale[1]), float(node.scale[2]));
      if (node.rotation.size() == 4)
        for (size_t c = 0; c < 4; ++c) a.rotation[c] = float(node.rotation[c]);
      for (int child : node.children)
        if (child >= 0 && size_t(child) < model_.nodes.size()) {
          out.nodes[size_t(child)].parent = int(n);
          ++parents[size_t(child)];
        }
    }
    std::set<std::pair<int, std::string>> driven;
    size_t weights = 0, cubic = 0;
    for (size_t k = 0; k < model_.animations.size(); ++k) {
      const tinygltf::Animation& animation = model_.animations[k];
      for (size_t c = 0; c < animation.channels.size(); ++c) {
        const tinygltf::AnimationChannel& channel = animation.channels[c];
        const std::string what = "animation " + std::to_string(k) + " channel " + std::to_string(c);
        if (channel.target_path == "weights") {
          ++weights;
          continue;
        }
        NodeChannel out1;
        if (channel.target_path == "translation")
          out1.path = NodeChannel::Path::Translation;
        else if (channel.target_path == "rotation")
          out1.path = NodeChannel::Path::Rotation;
        else if (channel.target_path == "scale")
          out1.path = NodeChannel::Path::Scale;
        else
          fail(path_, what + ": unknown target path '" + channel.target_path + "'");
        if (channel.target_node < 0 || size_t(channel.target_node) >= model_.nodes.size())
          fail(path_,
               what + ": target node " + std::to_string(channel.target_node) + " does not exist");
        if (!driven.insert({channel.target_node, channel.target_path}).second) continue;
        if (channel.sampler < 0 || size_t(channel.sampler) >= animation.samplers.size())
          fail(path_, what + ": sampler " + std::to_string(channel.sampler) + " does not exist");
        const tinygltf::AnimationSampler& sampler = animation.samplers[size_t(channel.sampler)];
        const bool spline = sampler.interpolation == "CUBICSPLINE";
        cubic += spline;
        out1.step = sampler.interpolation == "STEP";
        const AccessorView input = view(sampler.input, TINYGLTF_TYPE_SCALAR, what + " input");
        const int type =
            out1.path == NodeChannel::Path::Rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3;
        const AccessorView output = view(sampler.output, type, what + " output");
        if (input.count == 0) fail(path_, what + ": no keys");
        if (output.count != input.count * (spline ? 3 : 1))
          fail(path_, what + ": " + std::to_string(output.count) + " values for " +
                          std::to_string(input.count) + " key times");
        for (size_t i = 0; i < input.count; ++i) {
          const double t = value(input, i, 0);
          if (!std::isfinite(t) || t < 0 || (i > 0 && !(float(t) > out1.times.back())))
            fail(path_, what + ": key times must be finite, from 0 and increasing");
          out1.times.push_back(float(t));
          std::array<float, 4> v{0, 0, 0, 0};
          // A spline key is (in-tangent, value, out-tangent): take the value.
          const size_t element = spline ? 3 * i + 1 : i;
          for (int j = 0; j < output.components; ++j) {
            const double key = value(output, element, j);
            if (!std::isfinite(key)) fail(path_, what + ": a key value is not finite");
            // Animated translations and scales keep to the ranges of the nodes' own.
            if (out1.path != NodeChannel::Path::Rotation && !(std::abs(key) <= kMaxCoordinate))
              fail(path_, what + ": key value " + numberText(key) + " is beyond 1e6");
            v[size_t(j)] = float(key);
          }
          out1.values.push_back(v);
        }
        out.seconds = std::max(out.seconds, double(out1.times.back()));
        out.nodes[size_t(channel.target_node)].channels.push_back(std::move(out1));
      }
    }
    if (weights)
      contents_.warnings.push_back("morph-target weight animation ignored (" +
                                   std::to_string(weights) + " channel" + (weights > 1 ? "s" : "") +
                                   ")");
    if (cubic)
      contents_.warnings.push_back("cubic-spline keys played as linear between their values");
    // A part moves if its node or an ancestor is driven; a node reached through two parents
    // (a shared child) is not animated: its instances would need a tree each.
    bool shared = false;
    for (FilePart& part : contents_.parts) {
      bool moves = false, ambiguous = false;
      for (int n = part.node, depth = 0; n >= 0 && depth < int(kMaxNodeDepth);
           n = out.nodes[size_t(n)].parent, ++depth) {
        moves = moves || !out.nodes[size_t(n)].channels.empty();
        ambiguous = ambiguous || parents[size_t(n)] > 1;
      }
      shared = shared || (moves && ambiguous);
      if (!moves || ambiguous) part.node = -1;
    }
    if (shared)
      contents_.warnings.push_back(
          "animated nodes reached through shared children are shown at rest");
  }

  FilePart readPrimitive(const tinygltf::Primitive& primitive, const std::string& context) {
    FilePart part;
    part.context = context;
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      ++skippedPrimitives_;
      return part;
    }
    if (primitive.material >= 0) {
      if (size_t(primitive.material) >= contents_.materials.size())
        fail(path_,
             context + ": material " + std::to_string(primitive.material) + " does not exist");
      part.material = primitive.material;
    }
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) fail(path_, context + ": no POSITION attribute");
    const AccessorView positions =
        view(position->second, TINYGLTF_TYPE_VEC3, context + ": POSITION");
    part.positions.resize(positions.count);
    for (size_t i = 0; i < positions.count; ++i)
      for (int a = 0; a < 3; ++a) part.positions[i][a] = float(value(positions, i, a));

    if (const auto normal = primitive.attributes.find("NORMAL");
        normal != primitive.attributes.end()) {
      const AccessorView normals = view(normal->second, TINYGLTF_TYPE_VEC3, context + ": NORMAL");
      requireCount(normals, positions.count, context + ": NORMAL");
      part.normals.resize(normals.count);
      for (size_t i = 0; i < normals.count; ++i)
        for (int a = 0; a < 3; ++a) part.normals[i][a] = float(value(normals, i, a));
    }
    const int uvSet = part.material >= 0 ? uvSets_[size_t(part.material)] : 0;
    const std::string uvName = "TEXCOORD_" + std::to_string(uvSet);
    if (const auto uv = primitive.attributes.find(uvName); uv != primitive.attributes.end()) {
      const AccessorView uvs = view(uv->second, TINYGLTF_TYPE_VEC2, context + ": " + uvName);
      requireCount(uvs, positions.count, context + ": " + uvName);
      part.uvs.resize(uvs.count);
      // glTF puts v = 0 at the top of the image, Image::sampleBilinear at the bottom.
      for (size_t i = 0; i < uvs.count; ++i)
        part.uvs[i] = {float(value(uvs, i, 0)), 1.0f - float(value(uvs, i, 1))};
    }
    if (!primitive.targets.empty()) morphTargets_ = true;
    if (const auto color = primitive.attributes.find("COLOR_0");
        color != primitive.attributes.end())
      readColors(color->second, positions.count, context, part);

    std::vector<uint32_t> corners;
    if (primitive.indices >= 0) {
      const AccessorView indices =
          view(primitive.indices, TINYGLTF_TYPE_SCALAR, context + ": indices");
      if (indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
          indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(path_, context + ": indices must be unsigned integers");
      corners.resize(indices.count);
      for (size_t i = 0; i < indices.count; ++i) corners[i] = uint32_t(value(indices, i, 0));
    } else {
      corners.resize(positions.count);
      for (size_t i = 0; i < corners.size(); ++i) corners[i] = uint32_t(i);
    }
    assemble(mode, corners, context, part.indices);
    return part;
  }

  // Specification, "Topology Types": triangle i of a strip is (i, i+1+i%2, i+2-i%2), of a fan
  // (i+1, i+2, 0).
  void assemble(int mode, const std::vector<uint32_t>& v, const std::string& context,
                std::vector<uint32_t>& out) {
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (v.size() % 3 != 0)
        fail(path_, context + ": " + std::to_string(v.size()) +
                        " triangle corners is not a multiple of 3");
      out = v;
      return;
    }
    for (size_t i = 0; i + 2 < v.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
        out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
      else
        out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
    }
  }

  // COLOR_0 (specification, "Meshes"): VEC3 or VEC4 of floats, or of normalised unsigned
  // bytes or shorts; linear RGB, so no transfer function. The alpha of VEC4 is ignored.
  void readColors(int accessor, size_t positionCount, const std::string& context, FilePart& part) {
    const std::string what = context + ": COLOR_0";
    if (accessor < 0 || size_t(accessor) >= model_.accessors.size())
      fail(path_, what + ": accessor " + std::to_string(accessor) + " does not exist");
    const int type = model_.accessors[size_t(accessor)].type;
    if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4)
      fail(path_, what + ": must be VEC3 or VEC4");
    AccessorView colors = view(accessor, type, what);
    if (colors.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT &&
        colors.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        colors.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
      fail(path_, what + ": must be floats or normalised unsigned bytes or shorts");
    // The specification requires `normalized` for the integer types; read them as such even
    // when a writer forgot the flag.
    colors.normalized = true;
    requireCount(colors, positionCount, what);
    part.colors.resize(colors.count);
    for (size_t i = 0; i < colors.count; ++i)
      for (int a = 0; a < 3; ++a) part.colors[i][a] = float(value(colors, i, a));
    ++coloredPrimitives_;
  }

  void requireCount(const AccessorView& a, size_t count, const std::string& what) {
    if (a.count != count)
      fail(path_, what + ": has " + std::to_string(a.count) + " elements but POSITION has " +
                      std::to_string(count));
  }

  AccessorView view(int index, int type, const std::string& what) {
    if (index < 0 || size_t(index) >= model_.accessors.size())
      fail(path_, what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& accessor = model_.accessors[size_t(index)];
    if (accessor.type != type) fail(path_, what + ": accessor has the wrong type");
    if (accessor.sparse.isSparse) fail(path_, what + ": sparse accessors are not supported");
    if (accessor.bufferView < 0 || size_t(accessor.bufferView) >= model_.bufferViews.size())
      fail(path_, what + ": accessor has no valid buffer view");
    const tinygltf::BufferView& bufferView = model_.bufferViews[size_t(accessor.bufferView)];
    if (bufferView.buffer < 0 || size_t(bufferView.buffer) >= model_.buffers.size())
      fail(path_, what + ": buffer view has no valid buffer");
    const std::vector<unsigned char>& buffer = model_.buffers[size_t(bufferView.buffer)].data;

    AccessorView result;
    result.count = accessor.count;
    result.componentType = accessor.componentType;
    result.componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
    result.components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
    result.normalized = accessor.normalized;
    const int stride = accessor.ByteStride(bufferView);
    if (result.componentSize <= 0 || result.components <= 0 || stride <= 0)
      fail(path_, what + ": invalid component type or stride");
    result.stride = size_t(stride);
    if (bufferView.byteOffset > buffer.size() ||
        bufferView.byteLength > buffer.size() - bufferView.byteOffset)
      fail(path_, what + ": buffer view extends past the end of its buffer (truncated?)");
    if (result.count > 0) {
      const size_t element = size_t(result.componentSize * result.components);
      const size_t length = bufferView.byteLength;
      const bool fits =
          accessor.byteOffset <= length && element <= length - accessor.byteOffset &&
          (result.count - 1) <= (length - accessor.byteOffset - element) / result.stride;
      if (!fits)
        fail(path_, what + ": accessor reads past the end of its buffer view (truncated?)");
    }
    result.data = buffer.data() + bufferView.byteOffset + accessor.byteOffset;
    return result;
  }

  // Component c of element i as a number; normalised integers map to [0,1] or [-1,1]
  // (specification, "Animations": f = max(c / 127, -1) for signed bytes, c / 255 unsigned...).
  static double value(const AccessorView& a, size_t i, int c) {
    const unsigned char* p = a.data + i * a.stride + size_t(c * a.componentSize);
    auto load = [p]<typename T>(T) {
      T v;
      std::memcpy(&v, p, sizeof(T));
      return v;
    };
    switch (a.componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return double(load(float{}));
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const double v = load(int8_t{});
        return a.normalized ? std::max(v / 127.0, -1.0) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        const double v = load(uint8_t{});
        return a.normalized ? v / 255.0 : v;
      }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const double v = load(int16_t{});
        return a.normalized ? std::max(v / 32767.0, -1.0) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        const double v = load(uint16_t{});
        return a.normalized ? v / 65535.0 : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return double(load(uint32_t{}));
      case TINYGLTF_COMPONENT_TYPE_DOUBLE:
        return load(double{});
      default:
        return 0;
    }
  }

  void readMaterials() {
    std::map<int, int> imageIndex;  // glTF image -> FileContents::images
    for (size_t m = 0; m < model_.materials.size(); ++m) {
      const tinygltf::Material& source = model_.materials[m];
      FileMaterial material;
      material.material.name = source.name.empty() ? "material " + std::to_string(m) : source.name;
      const std::vector<double>& base = source.pbrMetallicRoughness.baseColorFactor;
      if (base.size() >= 3)
        material.material.diffuse = {float(base[0]), float(base[1]), float(base[2])};
      double strength = 1.0;
      if (auto ext = source.extensions.find("KHR_materials_emissive_strength");
          ext != source.extensions.end() && ext->second.Has("emissiveStrength"))
        strength = ext->second.Get("emissiveStrength").GetNumberAsDouble();
      if (source.emissiveFactor.size() == 3)
        material.material.emission = {float(source.emissiveFactor[0] * strength),
                                      float(source.emissiveFactor[1] * strength),
                                      float(source.emissiveFactor[2] * strength)};
      const tinygltf::TextureInfo& texture = source.pbrMetallicRoughness.baseColorTexture;
      uvSets_.push_back(texture.index >= 0 ? texture.texCoord : 0);
      if (texture.index >= 0)
        material.image = image(texture.index, material.material.name, imageIndex);
      contents_.materials.push_back(std::move(material));
    }
  }

  int image(int textureIndex, const std::string& materialName, std::map<int, int>& imageIndex) {
    const std::string where = "material '" + materialName + "': ";
    if (size_t(textureIndex) >= model_.textures.size())
      fail(path_, where + "texture " + std::to_string(textureIndex) + " does not exist");
    const int source = model_.textures[size_t(textureIndex)].source;
    if (source < 0 || size_t(source) >= model_.images.size()) {
      contents_.warnings.push_back(where + "texture has no image we can read; ignoring it");
      return -1;
    }
    auto [it, inserted] = imageIndex.try_emplace(source, -1);
    if (!inserted) return it->second;
    const auto decoded = decodedImages_.find(source);
    if (decoded == decodedImages_.end()) {
      contents_.warnings.push_back(where + "image " + std::to_string(source) +
                                   " could not be decoded; ignoring it");
      return -1;
    }
    contents_.images.push_back(std::move(decoded->second));
    it->second = int(contents_.images.size()) - 1;
    return it->second;
  }

  const std::string& path_;
  const tinygltf::Model& model_;
  std::map<int, Image>& decodedImages_;  // by glTF image index, from ImageLoader
  FileContents contents_;
  std::vector<int> uvSets_;             // TEXCOORD set of each material's base colour texture
  std::vector<bool> onPath_;            // nodes between the root and the one being visited
  std::vector<std::string> namedPath_;  // the visited node's and its ancestors' names
  size_t nodeInstances_ = 0;
  size_t skippedPrimitives_ = 0;
  // For the note.
  std::set<int> meshesUsed_;
  size_t orthographicCameras_ = 0, rangedLights_ = 0, coloredPrimitives_ = 0;
  bool morphTargets_ = false;
};

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) result.push_back(line);
  return result;
}

}  // namespace

FileContents readGltf(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  ImageLoader images;
  images.model = &model;
  loader.SetImageLoader(&ImageLoader::load, &images);
  tinygltf::FsCallbacks fs{};
  fs.FileExists = &tinygltf::FileExists;
  fs.ExpandFilePath = &tinygltf::ExpandFilePath;
  fs.ReadWholeFile = &readWholeFile;
  fs.WriteWholeFile = &tinygltf::WriteWholeFile;
  fs.user_data = nullptr;
  loader.SetFsCallbacks(fs);
  const std::string bytes = readFileBytes(path);
  // A .glb starts with the magic "glTF" (specification, "GLB File Format"); anything else is
  // read as JSON.
  const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() > size_t(UINT32_MAX)) fail(path, "file too large for glTF");
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, data,
                                                       unsigned(bytes.size()), folder)
                         : loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(),
                                                      unsigned(bytes.size()), folder);
  if (!ok && !images.problem.empty()) fail(path, images.problem);
  if (!ok) {
    std::string message;
    for (const std::string& line : lines(error)) message += (message.empty() ? "" : "; ") + line;
    fail(path, message.empty() ? "cannot parse the glTF file" : message);
  }
  FileContents contents = GltfReader(path, model, images.decoded).read();
  for (const std::string& line : lines(warning)) contents.warnings.push_back(line);
  return contents;
}

}  // namespace parallax::meshio
