// loadMeshFile: picks the reader by extension, then does what all formats share: validation,
// the move to world space, dropping degenerate triangles, and appending meshes, materials,
// textures and images to the scene.
#include "parallax/importer/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>

#include "parallax/core/parallel.h"
#include "parallax/importer/mesh_readers.h"
#include "parallax/importer/mesh_reading.h"
#include "parallax/io/input_file.h"

namespace parallax {

namespace {

using meshio::fail;
using meshio::FileContents;
using meshio::FilePart;

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

std::string describe(float value) {
  return std::isnan(value) ? "NaN" : "infinite";
}

std::string where(const FilePart& part) {
  return part.context.empty() ? "" : part.context + ": ";
}

// Throws for anything a renderer cannot use: non-finite numbers and indices out of range.
void validate(const std::string& path, const FilePart& part) {
  for (size_t i = 0; i < part.positions.size(); ++i)
    for (int axis = 0; axis < 3; ++axis)
      if (!std::isfinite(part.positions[i][axis]))
        fail(path, where(part) + "vertex " + std::to_string(i) + ": coordinate is " +
                       describe(part.positions[i][axis]));
  for (size_t i = 0; i < part.normals.size(); ++i)
    if (!isFinite(part.normals[i]))
      fail(path, where(part) + "vertex " + std::to_string(i) + ": normal is not finite");
  for (size_t i = 0; i < part.uvs.size(); ++i)
    if (!std::isfinite(part.uvs[i].x) || !std::isfinite(part.uvs[i].y))
      fail(path,
           where(part) + "vertex " + std::to_string(i) + ": texture coordinate is not finite");
  // Vertex colours (glTF COLOR_0, PLY red/green/blue, OBJ "v x y z r g b"): one per position,
  // finite, not negative.
  if (!part.colors.empty() && part.colors.size() != part.positions.size())
    fail(path, where(part) + std::to_string(part.colors.size()) + " vertex colours for " +
                   std::to_string(part.positions.size()) + " vertices");
  for (size_t i = 0; i < part.colors.size(); ++i)
    if (!isFinite(part.colors[i]) || part.colors[i].x < 0 || part.colors[i].y < 0 ||
        part.colors[i].z < 0)
      fail(path,
           where(part) + "vertex " + std::to_string(i) + ": colour is not finite or is negative");
  for (size_t i = 0; i < part.indices.size(); ++i)
    if (part.indices[i] >= part.positions.size())
      fail(path, where(part) + "triangle " + std::to_string(i / 3) + ": vertex index " +
                     std::to_string(part.indices[i]) + " is out of range (" +
                     std::to_string(part.positions.size()) + " vertices)");
}

// A triangle is degenerate if it repeats a vertex or has exactly zero area; such triangles
// cannot be hit and only cost time in the accelerator.
bool isDegenerate(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  return cross(b - a, c - a) == Vec3f(0.0f);
}

// Angle-weighted vertex normals with a crease angle, for a part whose file gave none: each
// face adds its unit normal weighted by its angle at the vertex (Thürmer and Wüthrich 1998,
// "Computing vertex normals from polygonal facets"; the weights do not depend on how a
// surface is split into triangles). A corner only takes the faces around its vertex whose
// normals are within the crease angle of its own face's, so faces meeting at a sharper edge
// keep separate normals; vertices get split where their corners' normals differ. Corners
// are matched by position (STL repeats every vertex per face), so seams in the file's vertex
// list do not show. `part` is in world space; `flip` says that the appender will swap corners
// 1 and 2 (a mirroring transform), so the front face is the other side.
// A vertex shared by more faces than this keeps its faces' own normals: comparing every face
// there with every other costs the square of their number (a hostile file could make one
// vertex the corner of millions), and real meshes stay far below it (the centre of a
// 4096-segment disc).
constexpr uint32_t kMaxSmoothedValence = 4096;

// Returns how many vertices were left faceted for exceeding kMaxSmoothedValence.
size_t generateNormals(FilePart& part, bool flip, float creaseDegrees) {
  const size_t triangles = part.indices.size() / 3;
  // Same position, same vertex: sorting the vertices by position puts equal ones side by side
  // (contiguous, unlike a node-based hash map, whose cache misses dominated on the dragon).
  // The positions are finite (validated) and -0 == +0 compares equal, so both weld.
  std::vector<uint32_t> order(part.positions.size());
  for (size_t v = 0; v < order.size(); ++v) order[v] = uint32_t(v);
  const auto& P = part.positions;
  auto less = [&](uint32_t a, uint32_t b) {
    if (P[a].x != P[b].x) return P[a].x < P[b].x;
    if (P[a].y != P[b].y) return P[a].y < P[b].y;
    return P[a].z < P[b].z;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<uint32_t> weld(P.size());
  uint32_t welded = 0;
  for (size_t i = 0; i < order.size(); ++i) {
    if (i > 0 && P[order[i]] != P[order[i - 1]]) ++welded;
    weld[order[i]] = welded;
  }
  const size_t weldCount = order.empty() ? 0 : welded + 1;

  // Unit face normals and corner angles; degenerate faces get weight 0 (they are dropped).
  std::vector<Vec3f> faceNormal(triangles, Vec3f(0.0f));
  std::vector<float> angle(triangles * 3, 0.0f);
  parallelFor(int64_t(triangles), 0, 1 << 14, [&](int64_t begin, int64_t end) {
    for (auto t = size_t(begin); t < size_t(end); ++t) {
      const Vec3f* p[3];
      for (int k = 0; k < 3; ++k) p[k] = &part.positions[part.indices[3 * t + size_t(k)]];
      const Vec3f n = cross(*p[1] - *p[0], *p[2] - *p[0]);
      const float len = length(n);
      if (!(len > 0.0f) || !std::isfinite(len)) continue;
      faceNormal[t] = n / (flip ? -len : len);
      for (int k = 0; k < 3; ++k) {
        // The corner's angle; atan2 of |e1 x e2| and e1 . e2 stays accurate near 0 and 180.
        const Vec3f e1 = *p[(k + 1) % 3] - *p[k], e2 = *p[(k + 2) % 3] - *p[k];
        angle[3 * t + size_t(k)] = std::atan2(length(cross(e1, e2)), dot(e1, e2));
      }
    }
  });

  // The corners around each welded vertex (compressed rows).
  std::vector<uint32_t> start(weldCount + 1, 0);
  for (uint32_t index : part.indices) ++start[weld[index] + 1];
  for (size_t w = 0; w < weldCount; ++w) start[w + 1] += start[w];
  std::vector<uint32_t> corners(part.indices.size()), fill(start.begin(), start.end() - 1);
  for (size_t c = 0; c < triangles * 3; ++c) corners[fill[weld[part.indices[c]]]++] = uint32_t(c);

  // Each corner's normal, in parallel over the welded vertices: a vertex's faces are gathered
  // once and every corner there sums them from that small copy (walking the corners in file
  // order instead fetched the same scattered faces again per corner). A corner reads only
  // its vertex's faces, so the result does not depend on the thread count.
  const float cosCrease = std::cos(creaseDegrees * std::numbers::pi_v<float> / 180.0f);
  std::vector<Vec3f> cornerNormal(triangles * 3);
  parallelFor(int64_t(weldCount), 0, 1 << 12, [&](int64_t begin, int64_t end) {
    std::vector<std::pair<Vec3f, float>> around;  // (face normal, angle) of each corner
    for (auto w = size_t(begin); w < size_t(end); ++w) {
      if (start[w + 1] - start[w] > kMaxSmoothedValence) {
        for (uint32_t i = start[w]; i < start[w + 1]; ++i)
          cornerNormal[corners[i]] = faceNormal[corners[i] / 3];
        continue;
      }
      around.clear();
      for (uint32_t i = start[w]; i < start[w + 1]; ++i)
        around.emplace_back(faceNormal[corners[i] / 3], angle[corners[i]]);
      for (uint32_t i = start[w]; i < start[w + 1]; ++i) {
        const Vec3f& own = around[i - start[w]].first;
        Vec3f sum(0.0f);
        for (const auto& [normal, weight] : around)
          if (dot(own, normal) >= cosCrease) sum += normal * weight;
        const float len = length(sum);
        cornerNormal[corners[i]] = len > 0.0f && std::isfinite(len) ? sum / len : own;
      }
    }
  });

  // One vertex per (file vertex, normal): corners of a smooth region sum the same faces in
  // the same order, so their normals are equal bit for bit. The vertices made from one file
  // vertex are chained (first[v], then next[]), in the order of their first corner.
  constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> first(part.positions.size(), kNone), next;
  std::vector<Vec3f> positions, normals;
  std::vector<Vec2f> uvs;
  std::vector<Vec3f> colors;
  positions.reserve(part.positions.size());
  normals.reserve(part.positions.size());
  next.reserve(part.positions.size());
  std::vector<uint32_t> indices(part.indices.size());
  for (size_t c = 0; c < triangles * 3; ++c) {
    const uint32_t v = part.indices[c];
    const Vec3f& n = cornerNormal[c];
    uint32_t* link = &first[v];
    while (*link != kNone && normals[*link] != n) link = &next[*link];
    if (*link == kNone) {
      *link = uint32_t(positions.size());  // before next grows: `link` may point into it
      positions.push_back(part.positions[v]);
      normals.push_back(n);
      next.push_back(kNone);
      if (!part.uvs.empty()) uvs.push_back(part.uvs[v]);
      if (!part.colors.empty()) colors.push_back(part.colors[v]);
      indices[c] = uint32_t(positions.size() - 1);
    } else {
      indices[c] = *link;
    }
  }
  part.positions = std::move(positions);
  part.normals = std::move(normals);
  part.uvs = std::move(uvs);
  part.colors = std::move(colors);
  part.indices = std::move(indices);
  size_t crowded = 0;
  for (size_t w = 0; w < weldCount; ++w) crowded += start[w + 1] - start[w] > kMaxSmoothedValence;
  return crowded;
}

// Collects the world-space meshes of one file, one per scene material, and creates the
// scene materials, textures and images the first time a kept triangle needs them.
class SceneAppender {
 public:
  SceneAppender(const std::string& path, const MeshLoadOptions& options, FileContents& contents,
                Scene& scene)
      : path_(path), options_(options), contents_(contents), scene_(scene) {
    prefix_ = options.name.empty() ? std::filesystem::path(path).stem().string() : options.name;
  }

  // `part` must have passed validate(). `fileFromReader` turns a Z-up file Y-up.
  void add(FilePart& part, const Transform& fileFromReader) {
    const Transform worldFromPart = options_.worldFromFile * fileFromReader * part.fileFromPart;
    for (Vec3f& p : part.positions) {
      p = worldFromPart.point(p);
      if (!isFinite(p))
        fail(path_, where(part) + "a vertex moved to world space overflows (transform too large)");
    }
    const bool hadNormals = !part.normals.empty();
    transformNormals(worldFromPart, part);
    const bool flip = worldFromPart.swapsHandedness();
    const bool generate = !hadNormals && options_.creaseDegrees > 0.0f;
    if (generate)
      if (const size_t crowded = generateNormals(part, flip, options_.creaseDegrees))
        scene_.warnings.push_back(path_ + ": " + where(part) + std::to_string(crowded) +
                                  (crowded == 1 ? " vertex" : " vertices") +
                                  " shared by more than " + std::to_string(kMaxSmoothedValence) +
                                  " triangles keep their faces' normals");
    (hadNormals ? fileNormals_ : generate ? generatedNormals_ : faceted_) = true;

    TriangleMesh* mesh = nullptr;
    Bounds3f partBounds;
    std::vector<uint32_t> remap(part.positions.size(), kUnused);
    for (size_t t = 0; t + 2 < part.indices.size(); t += 3) {
      uint32_t corner[3] = {part.indices[t], part.indices[t + 1], part.indices[t + 2]};
      if (isDegenerate(part.positions[corner[0]], part.positions[corner[1]],
                       part.positions[corner[2]])) {
        ++dropped_;
        continue;
      }
      if (flip) std::swap(corner[1], corner[2]);
      if (!mesh) mesh = &meshFor(part, worldFromPart);
      for (uint32_t v : corner) {
        if (remap[v] == kUnused) {
          remap[v] = uint32_t(mesh->positions.size());
          mesh->positions.push_back(part.positions[v]);
          if (!part.normals.empty()) mesh->normals.push_back(part.normals[v]);
          if (!part.uvs.empty()) mesh->uvs.push_back(part.uvs[v]);
          addColor(part, v, *mesh);
        }
        mesh->indices.push_back(remap[v]);
      }
      ++triangles_;
      for (uint32_t v : corner) partBounds.extend(part.positions[v]);
    }
    if (!partBounds.empty())
      for (const std::string& name : part.nodeNames) objectBounds(name).extend(partBounds);
  }

  // What was done, for Scene::imports.
  void record(const std::string& reader, UpAxis up) {
    Scene::ImportRecord r;
    r.file = path_;
    r.reader = reader;
    r.up = up == UpAxis::Z ? "z" : "y";
    std::vector<std::string> kinds;
    if (fileNormals_) kinds.push_back("file");
    if (generatedNormals_) {
      std::ostringstream text;
      text << "generated (crease " << options_.creaseDegrees << "°)";
      kinds.push_back(text.str());
    }
    if (faceted_) kinds.push_back("faceted");
    for (size_t i = 0; i < kinds.size(); ++i) r.normals += (i ? " + " : "") + kinds[i];
    if (kinds.empty()) r.normals = "none (no triangles)";
    r.triangles = triangles_;
    scene_.imports.push_back(std::move(r));
  }

  void finish() {
    const int firstNode = int(scene_.nodeAnimation.nodes.size());
    for (auto& [key, mesh] : meshes_) {
      // Parts with and without normals (or UVs) may share a material; the mesh then keeps
      // only what every vertex has.
      if (mesh.normals.size() != mesh.positions.size()) mesh.normals.clear();
      if (mesh.uvs.size() != mesh.positions.size()) mesh.uvs.clear();
      if (key.second >= 0) {  // hangs from an animated node: remember how to move it
        AnimatedMesh animated = animatedMeshes_.at(key.second);
        animated.mesh = uint32_t(scene_.meshes.size());
        animated.node = firstNode + key.second;
        scene_.nodeAnimation.meshes.push_back(animated);
      }
      if (!mesh.colors.empty()) mesh.colors.resize(mesh.positions.size(), Vec3f(1.0f));
      scene_.meshes.push_back(std::move(mesh));
    }
    if (!animatedMeshes_.empty()) appendNodes(contents_.nodeAnimation);
    for (auto& [name, bounds] : objects_) scene_.objects.push_back({name, path_, bounds});
    const size_t dropped = dropped_ + contents_.droppedDegenerate;
    if (dropped > 0)
      scene_.warnings.push_back(path_ + ": dropped " + std::to_string(dropped) +
                                " degenerate triangle" + (dropped == 1 ? "" : "s"));
    if (meshes_.empty()) scene_.warnings.push_back(path_ + ": contains no triangles");
  }

 private:
  static constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();

  // Vertex colours of the vertex just appended: parts with and without colours may share a
  // material, so a mesh with any colours gives the others white (the albedo unchanged).
  static void addColor(const FilePart& part, uint32_t v, TriangleMesh& mesh) {
    if (part.colors.empty() && mesh.colors.empty()) return;
    mesh.colors.resize(mesh.positions.size() - 1, Vec3f(1.0f));
    mesh.colors.push_back(part.colors.empty() ? Vec3f(1.0f) : part.colors[v]);
  }

  void transformNormals(const Transform& worldFromPart, FilePart& part) {
    for (Vec3f& n : part.normals) {
      n = worldFromPart.normal(n);
      const float len = length(n);
      if (!(len > 0.0f) || !std::isfinite(len)) {
        scene_.warnings.push_back(path_ + ": " + where(part) +
                                  "zero-length vertex normals; using flat shading");
        part.normals.clear();
        return;
      }
      n = n / len;
    }
  }

  // The file's node tree after the scene's nodes (another animated file's), parents shifted.
  void appendNodes(const NodeAnimation& file) {
    const int firstNode = int(scene_.nodeAnimation.nodes.size());
    for (AnimatedNode node : file.nodes) {
      if (node.parent >= 0) node.parent += firstNode;
      scene_.nodeAnimation.nodes.push_back(std::move(node));
    }
    scene_.nodeAnimation.seconds = std::max(scene_.nodeAnimation.seconds, file.seconds);
  }

  // Parts of one material share a mesh, except that a part hanging from an animated node gets
  // a mesh of its own node (it moves alone).
  TriangleMesh& meshFor(const FilePart& part, const Transform& worldFromPart) {
    const uint32_t material = sceneMaterial(part.material);
    auto [it, inserted] = meshes_.try_emplace({material, part.node});
    if (inserted && part.node >= 0) {
      // The part's vertices are stored posed at rest: worldFromPart undoes to the node's space.
      AnimatedMesh animated;
      animated.worldFromFile = worldFromPart.matrix() * part.fileFromPart.inverseMatrix();
      animated.restMeshFromWorld = worldFromPart.inverseMatrix();
      animatedMeshes_[part.node] = animated;
    }
    if (inserted) {
      it->second.material = material;
      const bool named = !options_.materialOverride && part.material >= 0;
      it->second.name = named ? prefix_ + "/" + scene_.materials[material].name : prefix_;
    }
    return it->second;
  }

  uint32_t sceneMaterial(int fileMaterial) {
    if (options_.materialOverride) return *options_.materialOverride;
    auto found = materials_.find(fileMaterial);
    if (found != materials_.end()) return found->second;
    Material material;
    if (fileMaterial < 0) {
      material.name = prefix_ + "/default";
      material.diffuse = Vec3f(0.7f);
    } else {
      const meshio::FileMaterial& source = contents_.materials[size_t(fileMaterial)];
      material = source.material;
      material.diffuseTexture = source.image >= 0 ? sceneTexture(source.image) : -1;
    }
    scene_.materials.push_back(std::move(material));
    const auto index = uint32_t(scene_.materials.size() - 1);
    materials_[fileMaterial] = index;
    return index;
  }

  int sceneTexture(int fileImage) {
    auto found = textures_.find(fileImage);
    if (found != textures_.end()) return found->second;
    scene_.images.push_back(std::move(contents_.images[size_t(fileImage)]));
    Texture texture;
    texture.kind = Texture::Kind::Image;
    texture.image = int(scene_.images.size()) - 1;
    scene_.textures.push_back(texture);
    const int index = int(scene_.textures.size()) - 1;
    textures_[fileImage] = index;
    return index;
  }

  const std::string& path_;
  const MeshLoadOptions& options_;
  FileContents& contents_;
  Scene& scene_;
  std::string prefix_;
  // By scene material and animated node (-1: none), in a stable order.
  std::map<std::pair<uint32_t, int>, TriangleMesh> meshes_;
  std::map<int, AnimatedMesh> animatedMeshes_;  // by file node
  // Named nodes' world bounds, in the order first met (at rest, as the meshes are stored).
  std::vector<std::pair<std::string, Bounds3f>> objects_;
  Bounds3f& objectBounds(const std::string& name) {
    for (auto& [known, bounds] : objects_)
      if (known == name) return bounds;
    return objects_.emplace_back(name, Bounds3f{}).second;
  }
  std::map<int, uint32_t> materials_;  // file material -> scene material
  std::map<int, int> textures_;        // file image -> scene texture
  size_t dropped_ = 0;
  size_t triangles_ = 0;
  bool fileNormals_ = false, generatedNormals_ = false, faceted_ = false;
};

}  // namespace

// The file's cameras and punctual lights moved to world space, and its note (docs/gltf.md).
static void addCamerasAndLights(const std::string& path, const MeshLoadOptions& options,
                                const FileContents& contents, Scene& scene) {
  const int note = contents.note.empty() ? -1 : int(scene.notes.size());
  if (!contents.note.empty()) scene.notes.push_back(path + ": " + contents.note);
  const Transform& world = options.worldFromFile;
  for (const meshio::FileCamera& source : contents.cameras) {
    const Vec3f eye = world.point(source.eye);
    const Vec3f forward = world.vector(source.forward), up = world.vector(source.up);
    if (!isFinite(eye) || !(length(cross(forward, up)) > 0) || !isFinite(forward) ||
        !isFinite(up)) {
      scene.warnings.push_back(path + ": camera '" + source.name +
                               "' has no usable world transform; ignoring it");
      continue;
    }
    NamedCamera camera;
    camera.name = source.name;
    camera.nodeName = source.nodeName;
    camera.source = path;
    camera.spec.eye = eye;
    camera.spec.lookAt = eye + normalize(forward);
    // Up across the line of sight (a sheared node may tilt it).
    const Vec3f f = normalize(forward);
    camera.spec.up = normalize(up - f * dot(up, f));
    camera.spec.fovDegrees = source.yfov * (180.0f / kPi);
    camera.aspectRatio = source.aspectRatio;
    camera.znear = source.znear;
    camera.note = note;
    scene.cameras.push_back(std::move(camera));
  }
  for (const meshio::FileLight& source : contents.lights) {
    Light light = source.light;
    light.position = world.point(light.position);
    if (light.kind != Light::Kind::Point) {
      const Vec3f d = world.vector(light.direction);
      if (!(length(d) > 0) || !isFinite(d)) continue;
      light.direction = normalize(d);
    }
    if (!isFinite(light.position)) continue;
    scene.lights.push_back(light);
  }
}

namespace {

bool ourFormat(const std::string& ext) {
  return ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".gltf" || ext == ".glb" ||
         ext == ".off";
}

}  // namespace

bool isMeshFile(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ourFormat(ext) || meshio::assimpReads(ext);
}

void loadMeshFile(const std::string& path, const MeshLoadOptions& options, Scene& scene) {
  requireRegularFile(path);
  std::error_code error;
  if (std::filesystem::file_size(path, error) == 0) fail(path, "file is empty");
  if (options.materialOverride && *options.materialOverride >= scene.materials.size())
    throw std::invalid_argument("loadMeshFile: material override " +
                                std::to_string(*options.materialOverride) +
                                " is not a scene material");

  if (!(options.creaseDegrees >= 0.0f && options.creaseDegrees <= 180.0f))
    throw std::invalid_argument("loadMeshFile: crease angle " +
                                std::to_string(options.creaseDegrees) + " is not in [0, 180]");

  const std::string ext = lowerExtension(path);
  FileContents contents;
  std::string reader = "parallax-" + ext.substr(ext.empty() ? 0 : 1);
  if (options.forceAssimp || !ourFormat(ext)) {
    if (!meshio::assimpReads(ext))
      fail(path, "unknown mesh format '" + ext +
                     "' (docs/import.md lists the formats; assimp does not know this one)");
    contents = meshio::readAssimp(path);
    reader = "assimp";
  } else if (ext == ".obj") {
    contents = meshio::readObj(path);
  } else if (ext == ".ply") {
    contents = meshio::readPly(path);
  } else if (ext == ".stl") {
    contents = meshio::readStl(path);
  } else if (ext == ".off") {
    contents = meshio::readOff(path);
  } else {
    contents = meshio::readGltf(path);
    reader = "parallax-gltf";
  }

  // The up axis (docs/import.md): what the file declares (FBX), else the format's convention.
  // The 3-D printing formats (STL, 3MF and AMF, whose specifications put the build platform
  // in the XY plane) and Blender are Z-up, and assimp leaves their axes alone; its Collada
  // (<up_axis>) and 3DS importers turn Z-up files Y-up themselves; glTF is Y-up by its
  // specification, and the scanned models in PLY and OBJ (Stanford's) are Y-up.
  // Splat files are trained in COLMAP's frame (y down, the cameras looking along +z).
  UpAxis up = options.up;
  if (up == UpAxis::Auto) up = contents.declaredUp;
  if (up == UpAxis::Auto)
    up = contents.splats                                                      ? UpAxis::MinusY
         : ext == ".stl" || ext == ".3mf" || ext == ".amf" || ext == ".blend" ? UpAxis::Z
                                                                              : UpAxis::Y;
  // Exact matrices, where rotate() would leave cos(90 deg) = 6e-17. Z up: -90 degrees about X,
  // (x, y, z) -> (x, z, -y), so that +Z becomes +Y. -Y up: 180 degrees about X, (x, y, z) ->
  // (x, -y, -z), so that a capture's cameras look along -z as the viewer of the display does.
  // Both are rotations: the handedness and the winding stay.
  Mat4 toY = Mat4::identity();
  if (up == UpAxis::Z) {
    toY.m[1] = {0, 0, 1, 0};
    toY.m[2] = {0, -1, 0, 0};
  } else if (up == UpAxis::MinusY) {
    toY.m[1] = {0, -1, 0, 0};
    toY.m[2] = {0, 0, -1, 0};
  }
  const Transform fileFromReader(toY);

  if (contents.splats) {
    Scene::ImportRecord record;
    record.file = path;
    record.reader = reader;
    record.up = upAxisName(up);
    record.splats = contents.splats->size();
    sortForLocality(*contents.splats);
    scene.splats.push_back(
        {path, std::move(*contents.splats), options.worldFromFile * fileFromReader});
    scene.imports.push_back(record);
    return;
  }
  // Validate everything before touching the scene, so a bad file leaves it unchanged.
  for (const FilePart& part : contents.parts) validate(path, part);
  SceneAppender appender(path, options, contents, scene);
  for (const std::string& warning : contents.warnings)
    scene.warnings.push_back(path + ": " + warning);
  for (FilePart& part : contents.parts) appender.add(part, fileFromReader);
  appender.finish();
  appender.record(reader, up);
  // Cameras and lights turn with the file's up axis as its meshes do.
  MeshLoadOptions placed = options;
  placed.worldFromFile = options.worldFromFile * fileFromReader;
  addCamerasAndLights(path, placed, contents, scene);
}

}  // namespace parallax
