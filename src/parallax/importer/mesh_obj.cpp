// Wavefront OBJ + MTL through tinyobjloader. We let tinyobjloader tokenise the file and the
// MTL, but triangulate and range-check faces ourselves: it silently skips quads with bad
// indices and reads unparsable numbers ("nan") as 0, so numbers are checked in a first pass.
// Materials: Kd -> diffuse, map_Kd -> diffuse texture (path relative to the OBJ's folder),
// Ke -> emission, Ks -> mirror for illum 3 and 5 (the MTL "ray-traced reflection" models).
// Polygons are split by triangulatePolygon, so concave ones come out right. Vertex colours
// ("v x y z r g b", an extension MeshLab and others write) are read when every vertex has
// them; they are display values, sRGB-encoded in [0, 1], and decoded to linear.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <sstream>
#include <unordered_map>

#include "parallax/importer/mesh_readers.h"
#include "parallax/io/image_file.h"
#include "parallax/io/input_file.h"

namespace parallax::meshio {
namespace {

// A face's relative (negative) or zero index, which must name one of the `defined` elements
// above its line. tinyobjloader 2.0rc10 (Debian 12) reads one that does not as an index we
// catch later, 2.0rc13 (Debian 13) refuses the file with its own message; checked here, the
// message is ours and the same with either. Components that are not integers are left to it.
void checkRelativeIndices(const std::string& path, size_t lineNumber, std::string_view corner,
                          const size_t defined[3]) {
  static const char* const names[3] = {"vertex", "texture coordinate", "normal"};
  for (int component = 0; component < 3 && !corner.empty(); ++component) {
    const size_t slash = std::min(corner.find('/'), corner.size());
    const std::string_view digits = corner.substr(0, slash);
    corner.remove_prefix(std::min(slash + 1, corner.size()));
    long long index = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size()) continue;
    if (index == 0 || (index < 0 && uint64_t(-index) > defined[component]))
      fail(path, "line " + std::to_string(lineNumber) + ": " + names[component] + " index " +
                     std::to_string(index) + " is out of range (" +
                     std::to_string(defined[component]) + " defined before it)");
  }
}

// Checks that the numbers of every v, vn and vt line parse and are finite, and that there
// are enough of them, so that no bad value reaches tinyobjloader (which would read it as 0);
// and that faces' relative indices name something above them.
void checkNumbers(const std::string& path, const std::string& folder, const std::string& text) {
  size_t defined[3] = {0, 0, 0};  // vertices, texture coordinates, normals so far
  size_t lineNumber = 0;
  for (size_t pos = 0; pos < text.size();) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    TextTokens words(std::string_view(text).substr(pos, end - pos));
    pos = end + 1;
    ++lineNumber;
    const std::string_view keyword = words.next();
    size_t needed = 0;
    std::string what;
    if (keyword == "v")
      needed = 3, what = "vertex coordinate", ++defined[0];
    else if (keyword == "vn")
      needed = 3, what = "normal", ++defined[2];
    else if (keyword == "vt")
      needed = 1, what = "texture coordinate", ++defined[1];
    else if (keyword == "f") {
      for (std::string_view corner = words.next(); !corner.empty(); corner = words.next())
        checkRelativeIndices(path, lineNumber, corner, defined);
      continue;
    } else if (keyword == "mtllib") {
      // tinyobjloader opens these itself: a folder, a device or a FIFO must not reach it.
      for (std::string_view name = words.next(); !name.empty(); name = words.next()) {
        const std::string file = (std::filesystem::path(folder) / std::string(name)).string();
        std::error_code error;
        if (std::filesystem::exists(file, error)) requireRegularFile(file);
      }
      continue;
    } else
      continue;
    const std::string at = "line " + std::to_string(lineNumber) + ": ";
    size_t count = 0;
    for (std::string_view token = words.next(); !token.empty(); token = words.next(), ++count) {
      double value = 0;
      if (!parseNumber(token, value))
        fail(path, at + what + " '" + std::string(token) + "' is not a number");
      if (!std::isfinite(value))
        fail(path, at + what + " is " + (std::isnan(value) ? "NaN" : "infinite"));
    }
    if (count < needed)
      fail(path, at + "'" + std::string(keyword) + "' needs " + std::to_string(needed) +
                     " numbers, found " + std::to_string(count));
  }
}

// A missing texture is a warning (the colour alone is used); a texture that is there but is
// no regular file, too large or not an image is an error naming it (readImage).
bool loadTexture(const std::string& file, Image& image, std::string& problem) {
  std::error_code error;
  if (!std::filesystem::exists(file, error)) return problem = "file not found", false;
  image = readImage(file);
  return true;
}

Vec3f toVec3(const tinyobj::real_t* v) {
  return {float(v[0]), float(v[1]), float(v[2])};
}

void readMaterials(const std::vector<tinyobj::material_t>& source, const std::string& folder,
                   FileContents& contents) {
  std::map<std::string, int> imageByFile;
  for (const tinyobj::material_t& m : source) {
    FileMaterial material;
    material.material.name = m.name;
    material.material.diffuse = toVec3(m.diffuse);
    material.material.emission = toVec3(m.emission);
    // Ke is the emission. Files from before Ke (the classic Cornell box that tinyobjloader
    // and others ship: its lamp is "Ka 20 20 20") put it in the ambient colour, where a
    // reflectance above 1 makes no sense otherwise: read such a Ka as the emission.
    const Vec3f ambient = toVec3(m.ambient);
    if (material.material.emission == Vec3f(0.0f) && maxComponent(ambient) > 1.0f) {
      material.material.emission = ambient;
      contents.warnings.push_back("material '" + m.name +
                                  "': no Ke, and Ka above 1; reading Ka as its emission");
    }
    if (m.illum == 3 || m.illum == 5) material.material.mirror = toVec3(m.specular);
    if (!m.diffuse_texname.empty()) {
      std::string name = m.diffuse_texname;
      std::replace(name.begin(), name.end(), '\\', '/');  // files written on Windows
      const std::string file = (std::filesystem::path(folder) / name).string();
      auto [it, inserted] = imageByFile.try_emplace(file, -1);
      std::string problem;
      Image image;
      if (inserted && loadTexture(file, image, problem)) {
        contents.images.push_back(std::move(image));
        it->second = int(contents.images.size()) - 1;
      } else if (inserted) {
        contents.warnings.push_back("material '" + m.name + "': cannot load texture '" + file +
                                    "' (" + problem + "); using its colour alone");
      }
      material.image = it->second;
    }
    contents.materials.push_back(std::move(material));
  }
}

// Builds one part per material, merging OBJ corners that share (v, vt, vn) into one vertex.
class PartBuilder {
 public:
  PartBuilder(const tinyobj::attrib_t& attrib, int material) : attrib_(attrib) {
    part_.material = material;
  }

  uint32_t corner(const tinyobj::index_t& index) {
    const Key key{index.vertex_index, index.texcoord_index, index.normal_index};
    auto [it, inserted] = vertices_.try_emplace(key, uint32_t(part_.positions.size()));
    if (!inserted) return it->second;
    part_.positions.push_back(toVec3(&attrib_.vertices[3 * size_t(index.vertex_index)]));
    // tinyobjloader keeps the colours only when every v line has them (vertex_color = false:
    // no white fallback), one triple per vertex.
    if (attrib_.colors.size() == attrib_.vertices.size()) {
      const Vec3f c = toVec3(&attrib_.colors[3 * size_t(index.vertex_index)]);
      part_.colors.push_back({srgbToLinear(std::clamp(c.x, 0.0f, 1.0f)),
                              srgbToLinear(std::clamp(c.y, 0.0f, 1.0f)),
                              srgbToLinear(std::clamp(c.z, 0.0f, 1.0f))});
    }
    if (index.normal_index >= 0)
      part_.normals.push_back(toVec3(&attrib_.normals[3 * size_t(index.normal_index)]));
    else
      missingNormals_ = true;
    if (index.texcoord_index >= 0) {
      const tinyobj::real_t* t = &attrib_.texcoords[2 * size_t(index.texcoord_index)];
      part_.uvs.push_back({float(t[0]), float(t[1])});
    } else {
      missingUvs_ = true;
    }
    return it->second;
  }

  void polygon(const std::vector<uint32_t>& corners) {
    triangulatePolygon(part_.positions, corners, part_.indices);
  }

  FilePart finish() {
    // Normals and UVs are all-or-nothing per mesh.
    if (missingNormals_) part_.normals.clear();
    if (missingUvs_) part_.uvs.clear();
    return std::move(part_);
  }

 private:
  struct Key {
    int v, vt, vn;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    size_t operator()(const Key& k) const {
      return (size_t(uint32_t(k.v)) * 0x9E3779B97F4A7C15ull) ^
             (size_t(uint32_t(k.vt)) * 0xC2B2AE3D27D4EB4Full) ^ size_t(uint32_t(k.vn));
    }
  };
  const tinyobj::attrib_t& attrib_;
  FilePart part_;
  std::unordered_map<Key, uint32_t, KeyHash> vertices_;
  bool missingNormals_ = false;
  bool missingUvs_ = false;
};

void checkIndex(const std::string& path, size_t face, const char* what, int index, size_t count,
                bool optional) {
  if (optional && index == -1) return;
  if (index >= 0 && size_t(index) < count) return;
  fail(path, "face " + std::to_string(face) + ": " + what + " index " +
                 (index < 0 ? "before the first one" : std::to_string(index + 1)) +
                 " is out of range (" + std::to_string(count) + " defined)");
}

}  // namespace

FileContents readObj(const std::string& path) {
  const std::string folder = std::filesystem::path(path).parent_path().string();
  checkNumbers(path, folder.empty() ? "." : folder, readFileBytes(path));

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  config.mtl_search_path = folder.empty() ? "." : folder;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string error = reader.Error();
    while (!error.empty() && (error.back() == '\n' || error.back() == '.')) error.pop_back();
    fail(path, error.empty() ? "cannot parse the OBJ file" : error);
  }

  FileContents contents;
  std::istringstream warnings(reader.Warning());
  for (std::string line; std::getline(warnings, line);)
    if (!line.empty()) contents.warnings.push_back(line);
  readMaterials(reader.GetMaterials(), config.mtl_search_path, contents);

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const size_t vertexCount = attrib.vertices.size() / 3;
  const size_t normalCount = attrib.normals.size() / 3;
  const size_t uvCount = attrib.texcoords.size() / 2;
  std::map<int, PartBuilder> builders;
  std::vector<uint32_t> polygon;
  size_t face = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    size_t next = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face) {
      const size_t corners = shape.mesh.num_face_vertices[f];
      int material = shape.mesh.material_ids[f];
      if (material < 0 || size_t(material) >= contents.materials.size()) material = -1;
      PartBuilder& builder = builders.try_emplace(material, attrib, material).first->second;
      polygon.clear();
      for (size_t k = 0; k < corners; ++k) {
        const tinyobj::index_t& index = shape.mesh.indices[next++];
        checkIndex(path, face, "vertex", index.vertex_index, vertexCount, false);
        checkIndex(path, face, "normal", index.normal_index, normalCount, true);
        checkIndex(path, face, "texture coordinate", index.texcoord_index, uvCount, true);
        polygon.push_back(builder.corner(index));
      }
      if (corners < 3) ++contents.droppedDegenerate;
      builder.polygon(polygon);
    }
  }
  for (auto& [material, builder] : builders) contents.parts.push_back(builder.finish());
  return contents;
}

}  // namespace parallax::meshio
