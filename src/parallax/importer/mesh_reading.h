// Private to the importer: the common shape every mesh format reader produces, and small
// text helpers the readers share (mesh_reading.cpp). loadMeshFile (mesh_file.cpp) validates
// what the readers return (mesh_readers.h), moves it into world space, drops degenerate
// triangles and appends it to the scene, so the readers only decode their format.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "parallax/core/transform.h"
#include "parallax/image/image.h"
#include "parallax/importer/up_axis.h"
#include "parallax/scene/gaussians.h"
#include "parallax/scene/scene.h"

namespace parallax::meshio {

// Triangles with one material, in the file's own space.
struct FilePart {
  std::string context;     // where in the file, for messages ("mesh 'wheel' primitive 0")
  int material = -1;       // index into FileContents::materials; -1: the default material
  Transform fileFromPart;  // glTF node transform; identity for the other formats
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;     // empty or one per position
  std::vector<Vec2f> uvs;         // empty or one per position; v = 0 is the image's bottom row
  std::vector<uint32_t> indices;  // three per triangle, not yet range-checked
  // glTF: the node the part hangs from when it or an ancestor is animated, an index into
  // FileContents::nodeAnimation.nodes; -1 otherwise.
  int node = -1;
  // The names of the node that instances it and of its named ancestors, nearest first (glTF,
  // assimp): the objects it belongs to (--focus-on).
  std::vector<std::string> nodeNames;
  std::vector<Vec3f> colors;  // vertex colours, linear RGB: empty or one per position
};

struct FileMaterial {
  Material material;  // diffuseTexture is ignored; `image` names the texture
  int image = -1;     // index into FileContents::images, or -1
};

// A camera and a punctual light of a glTF file (docs/gltf.md), in the file's space: the
// node's world transform already applied, the loader's worldFromFile not yet.
struct FileCamera {
  std::string name;
  std::string nodeName;    // the camera's node's name ("": none)
  Vec3f eye, forward, up;  // forward and up: not necessarily unit
  float yfov = 0;          // radians
  float aspectRatio = 0;   // 0: not given
  float znear = 0;
};
struct FileLight {
  Light light;  // Point, Directional or Spot; position and direction in the file's space
};

struct FileContents {
  std::vector<FilePart> parts;
  std::vector<FileCamera> cameras;
  std::vector<FileLight> lights;
  std::string note;  // what was taken and ignored (glTF), without the file name
  std::vector<FileMaterial> materials;
  std::vector<Image> images;          // linear RGB
  std::vector<std::string> warnings;  // without the file name; loadMeshFile adds it
  size_t droppedDegenerate = 0;       // faces a reader dropped itself (fewer than 3 corners)
  NodeAnimation nodeAnimation;        // glTF: the node tree and its channels (no meshes yet)
  // The up axis the file itself declares (FBX's UpAxis metadata); Auto if it says nothing.
  UpAxis declaredUp = UpAxis::Auto;
  // A splat file's Gaussians (a 3DGS PLY: splat_ply.h), in the file's space, instead of parts.
  std::optional<GaussianCloud> splats;
};

// Splits the polygon `corners` (indices into `positions`, in order) into triangles appended
// to `out`, keeping its winding: a convex polygon as a fan (a quad along its shorter
// diagonal), a concave one by ear clipping. Fewer than 3 corners give nothing.
void triangulatePolygon(const std::vector<Vec3f>& positions, const std::vector<uint32_t>& corners,
                        std::vector<uint32_t>& out);

// Throws the InputError for `path`, with control characters in the message escaped.
[[noreturn]] void fail(const std::string& path, const std::string& message);

// The whole file; throws InputError if it is not a regular file or cannot be opened or read.
std::string readFileBytes(const std::string& path);

// Whitespace-separated tokens of a text, with the line each one is on (for messages).
class TextTokens {
 public:
  explicit TextTokens(std::string_view text, size_t line = 1) : text_(text), line_(line) {}

  // The next token, or an empty view at the end of the text.
  std::string_view next();
  // Skips what is left of the current line (e.g. an STL solid's name).
  void skipLine();
  bool atEnd();
  // Line of the token last returned by next().
  size_t line() const { return tokenLine_; }

 private:
  void skipSpace();
  std::string_view text_;
  size_t pos_ = 0;
  size_t line_;
  size_t tokenLine_ = 0;
};

// Parses a whole token as a number; false if the token is not one. "nan" and "inf" parse, so
// that loadMeshFile can report them as such.
bool parseNumber(std::string_view token, double& value);
bool parseInteger(std::string_view token, int64_t& value);

// The shortest text that reads back as `value` ("7", "0.25", "1e+300", "nan"): a number in a
// message as the file gave it, never through an integer conversion.
std::string numberText(double value);

}  // namespace parallax::meshio
