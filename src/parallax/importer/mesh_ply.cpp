// PLY meshes (the format itself: ply_format.h). Reads vertex x y z, optional nx ny nz and u v (also
// named s t, texture_u texture_v, texture_s texture_t), red green blue (vertex colours, also
// diffuse_red ...; see colorScale) and face lists named vertex_indices or vertex_index, split into
// triangle fans. Every other element and property is read past and ignored.
#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>

#include "parallax/importer/mesh_readers.h"
#include "parallax/importer/ply_format.h"
#include "parallax/importer/splat_ply.h"

namespace parallax::meshio {
namespace {

// Which vertex property feeds which attribute; -1 where the file has none.
struct VertexLayout {
  int position[3] = {-1, -1, -1};
  int normal[3] = {-1, -1, -1};
  int uv[2] = {-1, -1};
  int color[3] = {-1, -1, -1};

  explicit VertexLayout(const Element& vertex) {
    for (size_t i = 0; i < vertex.properties.size(); ++i) {
      const Property& p = vertex.properties[i];
      if (p.isList) continue;
      const std::string& n = p.name;
      const int index = int(i);
      if (n == "x") position[0] = index;
      if (n == "y") position[1] = index;
      if (n == "z") position[2] = index;
      if (n == "nx") normal[0] = index;
      if (n == "ny") normal[1] = index;
      if (n == "nz") normal[2] = index;
      if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s") uv[0] = index;
      if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t") uv[1] = index;
      if (n == "red" || n == "diffuse_red") color[0] = index;
      if (n == "green" || n == "diffuse_green") color[1] = index;
      if (n == "blue" || n == "diffuse_blue") color[2] = index;
    }
  }
  bool hasColor() const { return color[0] >= 0 && color[1] >= 0 && color[2] >= 0; }
  bool hasPosition() const { return position[0] >= 0 && position[1] >= 0 && position[2] >= 0; }
  bool hasNormal() const { return normal[0] >= 0 && normal[1] >= 0 && normal[2] >= 0; }
  bool hasUv() const { return uv[0] >= 0 && uv[1] >= 0; }
};

class PlyParser {
 public:
  PlyParser(const std::string& path, const std::string& bytes)
      : path_(path),
        header_(parsePlyHeader(path, bytes, headerWarnings_)),
        values_(path, bytes, header_) {}

  FileContents parse() {
    contents_.warnings = std::move(headerWarnings_);
    const Element* vertex = find("vertex");
    if (!vertex) fail(path_, "no vertex element");
    vertexCount_ = vertex->count;
    if (!VertexLayout(*vertex).hasPosition())
      fail(path_, "the vertex element lacks one of the properties x, y, z");
    // Face indices refer to the one vertex element: a second one (or a second face element)
    // makes the file ambiguous.
    for (const char* name : {"vertex", "face"})
      if (std::count_if(header_.elements.begin(), header_.elements.end(),
                        [name](const Element& e) { return e.name == name; }) > 1)
        fail(path_, std::string("the header declares more than one '") + name + "' element");
    for (const Element& element : header_.elements) {
      if (element.name == "vertex")
        readVertices(element);
      else if (element.name == "face")
        readFaces(element);
      else
        skip(element);
    }
    std::vector<uint32_t> polygon;
    size_t next = 0;
    for (uint32_t size : polygonSizes_) {
      polygon.assign(polygonCorners_.begin() + std::ptrdiff_t(next),
                     polygonCorners_.begin() + std::ptrdiff_t(next + size));
      next += size;
      triangulatePolygon(part().positions, polygon, part().indices);
    }
    return std::move(contents_);
  }

 private:
  const Element* find(const std::string& name) const {
    for (const Element& e : header_.elements)
      if (e.name == name) return &e;
    return nullptr;
  }

  void readVertices(const Element& element) {
    checkCountFits(path_, element, values_);
    const VertexLayout layout(element);
    if (!layout.hasPosition())
      fail(path_, "the vertex element lacks one of the properties x, y, z");
    FilePart& part = this->part();
    part.positions.resize(element.count);
    if (layout.hasNormal()) part.normals.resize(element.count);
    if (layout.hasUv()) part.uvs.resize(element.count);
    if (layout.hasColor()) part.colors.resize(element.count);
    std::vector<double> scalars(element.properties.size());
    for (size_t v = 0; v < element.count; ++v) {
      const std::string where = "vertex " + std::to_string(v);
      for (size_t i = 0; i < element.properties.size(); ++i) {
        const Property& p = element.properties[i];
        if (p.isList)
          skipList(p, where);
        else
          scalars[i] = values_.read(p.type, where);
      }
      for (int a = 0; a < 3; ++a) part.positions[v][a] = float(scalars[size_t(layout.position[a])]);
      if (layout.hasNormal())
        for (int a = 0; a < 3; ++a) part.normals[v][a] = float(scalars[size_t(layout.normal[a])]);
      if (layout.hasUv())
        part.uvs[v] = {float(scalars[size_t(layout.uv[0])]), float(scalars[size_t(layout.uv[1])])};
      if (layout.hasColor())
        for (int a = 0; a < 3; ++a) {
          const Property& p = element.properties[size_t(layout.color[a])];
          part.colors[v][a] = plyColor(scalars[size_t(layout.color[a])], p.type);
        }
    }
  }

  // PLY colours (MeshLab, Blender, scanners) are display values: 8-bit codes 0..255 (16-bit
  // 0..65535, floats 0..1) in sRGB, decoded to linear with the sRGB transfer function
  // (IEC 61966-2-1). Values outside the range are clamped into it.
  static float plyColor(double value, Type type) {
    double scale = 1.0;
    if (type == Type::UInt8 || type == Type::Int8) scale = 255.0;
    if (type == Type::UInt16 || type == Type::Int16) scale = 65535.0;
    if (type == Type::UInt32 || type == Type::Int32) scale = 4294967295.0;
    if (!std::isfinite(value)) return float(value);  // loadMeshFile reports it
    const double encoded = std::clamp(value / scale, 0.0, 1.0);
    // A code outside 0..255 (an ASCII file may write one) is clamped like the others.
    if (type == Type::UInt8 && value >= 0 && value <= 255) return srgb8ToLinear(uint8_t(value));
    return srgbToLinear(float(encoded));
  }

  void readFaces(const Element& element) {
    checkCountFits(path_, element, values_);
    int indexProperty = -1;
    for (size_t i = 0; i < element.properties.size(); ++i) {
      const Property& p = element.properties[i];
      if (p.name == "vertex_indices" || p.name == "vertex_index") {
        if (!p.isList) fail(path_, "face property '" + p.name + "' is not a list");
        indexProperty = int(i);
      }
    }
    if (indexProperty < 0) fail(path_, "the face element has no vertex_indices list");
    std::vector<uint32_t> polygon;
    for (size_t f = 0; f < element.count; ++f) {
      const std::string where = "face " + std::to_string(f);
      for (size_t i = 0; i < element.properties.size(); ++i) {
        const Property& p = element.properties[i];
        if (int(i) != indexProperty) {
          if (p.isList)
            skipList(p, where);
          else
            values_.read(p.type, where);
          continue;
        }
        const size_t n = listLength(p, where);
        polygon.clear();
        for (size_t k = 0; k < n; ++k) polygon.push_back(vertexIndex(p.type, where));
      }
      if (polygon.size() < 3) ++contents_.droppedDegenerate;
      // Faces may come before the vertices; triangulate once both are read.
      polygonSizes_.push_back(uint32_t(polygon.size()));
      polygonCorners_.insert(polygonCorners_.end(), polygon.begin(), polygon.end());
    }
  }

  uint32_t vertexIndex(Type type, const std::string& where) {
    const double value = values_.read(type, where);
    // The range first, in double: a float index beyond the integers (1e300, NaN) must not
    // reach an integer conversion, which would be undefined. Quoted as the file gives it.
    const double end = std::min(double(vertexCount_), 4294967296.0);
    if (!(value >= 0 && value < end))
      fail(path_, where + ": vertex index " + numberText(value) + " is out of range (" +
                      std::to_string(vertexCount_) + " vertices)");
    if (value != std::floor(value))
      fail(path_, where + ": vertex index " + numberText(value) + " is not an integer");
    return uint32_t(value);
  }

  size_t listLength(const Property& p, const std::string& where) {
    const double n = values_.read(p.countType, where);
    if (n < 0) fail(path_, where + ": negative list length");
    return size_t(n);
  }

  void skipList(const Property& p, const std::string& where) {
    const size_t n = listLength(p, where);
    for (size_t k = 0; k < n; ++k) values_.read(p.type, where);
  }

  void skip(const Element& element) {
    if (element.properties.empty()) return;  // nothing to read, however many items
    checkCountFits(path_, element, values_);
    for (size_t item = 0; item < element.count; ++item) {
      const std::string where = element.name + " " + std::to_string(item);
      for (const Property& p : element.properties) {
        if (p.isList)
          skipList(p, where);
        else
          values_.read(p.type, where);
      }
    }
  }

  FilePart& part() {
    if (contents_.parts.empty()) contents_.parts.emplace_back();
    return contents_.parts.front();
  }

  const std::string& path_;
  std::vector<std::string> headerWarnings_;  // filled while header_ is initialised
  Header header_;
  ValueReader values_;
  uint64_t vertexCount_ = 0;
  std::vector<uint32_t> polygonSizes_, polygonCorners_;  // faces, before triangulation
  FileContents contents_;
};

}  // namespace

FileContents readPly(const std::string& path) {
  {
    std::vector<std::string> warnings;
    if (std::optional<GaussianCloud> splats = readSplatsInBlocks(path, warnings)) {
      FileContents contents;
      contents.warnings = std::move(warnings);
      contents.splats = std::move(splats);
      return contents;
    }
  }
  const std::string bytes = readFileBytes(path);
  // A mesh or Gaussian splats, by the vertex element's properties (docs/splats.md, "Files").
  std::vector<std::string> warnings;
  const Header header = parsePlyHeader(path, bytes, warnings);
  if (holdsSplats(header)) {
    FileContents contents;
    contents.warnings = std::move(warnings);
    contents.splats = readSplats(path, bytes, header);
    return contents;
  }
  return PlyParser(path, bytes).parse();
}

}  // namespace parallax::meshio
