// OFF reader (Geomview's Object File Format, http://www.geomview.org/docs/html/OFF.html, the
// format of the Princeton Shape Benchmark and ModelNet): a keyword line "[ST][C][N][n]OFF",
// the counts "vertices faces edges", one vertex per line ("x y z [nx ny nz] [r g b [a]]
// [s t]", in that order for the prefixes N, C and ST) and one face per line
// ("n i0 ... i(n-1) [r g b [a]]", indices from 0), '#' starting a comment. Faces are split by
// triangulatePolygon. Colours are display values like PLY's: 8-bit codes when any component
// of the file's vertex (or face) colours is above 1 (MeshLab writes 0..255), else fractions
// 0..1 (Geomview's own convention), sRGB-encoded, decoded to linear; alpha is ignored. A
// face's colour gives its corners vertices of their own. Refused with a message: binary OFF,
// 4-D and n-D files other than 3-D, counts the file cannot hold (checked before anything is
// allocated), indices out of range and numbers that are not finite, each naming its line.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "parallax/importer/mesh_readers.h"

namespace parallax::meshio {
namespace {

// The smallest record of each kind, in bytes of text: a vertex is at least "0 0 0\n", a face
// at least "0\n". A header whose counts need more than the bytes after it is refused before
// any memory is reserved for them (an OFF of 25 bytes may announce 10^9 vertices).
constexpr uint64_t kMinVertexBytes = 6;
constexpr uint64_t kMinFaceBytes = 2;
// Counts are stored in 32-bit indices.
constexpr int64_t kMaxCount = std::numeric_limits<int32_t>::max();

struct Prefixes {
  bool uv = false, color = false, normal = false;
};

// One line at a time, without its comment; blank and comment-only lines are skipped.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}

  // The tokens of the next line that has any, false at the end of the text.
  bool next(std::vector<std::string_view>& tokens) {
    tokens.clear();
    while (tokens.empty() && pos_ < text_.size()) {
      const size_t end = std::min(text_.find('\n', pos_), text_.size());
      std::string_view line = text_.substr(pos_, end - pos_);
      line = line.substr(0, std::min(line.find('#'), line.size()));
      pos_ = end + 1;
      ++number_;
      TextTokens words(line);
      for (std::string_view token = words.next(); !token.empty(); token = words.next())
        tokens.push_back(token);
    }
    return !tokens.empty();
  }

  size_t number() const { return number_; }  // of the line last returned
  size_t remaining() const { return pos_ < text_.size() ? text_.size() - pos_ : 0; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  size_t number_ = 0;
};

class OffParser {
 public:
  OffParser(const std::string& path, std::string_view bytes) : path_(path), lines_(bytes) {}

  FileContents parse() {
    std::vector<std::string_view> tokens;
    readHeader(tokens);
    readVertices(tokens);
    readFaces(tokens);
    size_t extra = 0;
    while (lines_.next(tokens)) ++extra;
    if (extra > 0)
      contents_.warnings.push_back("ignored " + std::to_string(extra) + " line" +
                                   (extra == 1 ? "" : "s") + " after the last face");
    finishColors();
    return std::move(contents_);
  }

 private:
  [[noreturn]] void failAt(const std::string& message) const {
    fail(path_, "line " + std::to_string(lines_.number()) + ": " + message);
  }

  // The keyword ("OFF", "COFF", "NOFF", "STCNOFF", ...), then the counts, on its line or the
  // next. The keyword may be left out (Geomview allows it); ModelNet's files glue the first
  // count to it ("OFF490 518 0").
  void readHeader(std::vector<std::string_view>& tokens) {
    if (!lines_.next(tokens)) fail(path_, "no header (not an OFF file?)");
    std::vector<std::string_view> rest;  // what follows the keyword on its line
    const std::string_view keyword = tokens[0];
    const size_t off = keyword.find("OFF");
    int64_t ignored = 0;
    if (off != std::string_view::npos) {
      const std::string_view glued = keyword.substr(off + 3);
      if (!glued.empty() && !parseInteger(glued, ignored))
        failAt("unknown keyword '" + std::string(keyword) + "' (not an OFF file?)");
      if (!glued.empty()) rest.push_back(glued);
      rest.insert(rest.end(), tokens.begin() + 1, tokens.end());
      if (!rest.empty() && rest[0] == "BINARY")
        failAt("binary OFF ('" + std::string(keyword) +
               " BINARY') is not supported; convert it to ASCII OFF or to PLY (e.g. with "
               "MeshLab)");
      const bool dimension = readPrefixes(keyword.substr(0, off));
      if (dimension) {  // "nOFF": the dimension comes first, on this line or the next
        if (rest.empty() && !lines_.next(rest))
          fail(path_, "the file ends before the dimension of '" + std::string(keyword) + "'");
        int64_t n = 0;
        if (!parseInteger(rest[0], n))
          failAt("'" + std::string(keyword) + "' needs the dimension after it, found '" +
                 std::string(rest[0]) + "'");
        if (n != 3) failAt("a " + std::to_string(n) + "-D OFF is not supported, only 3-D");
        rest.erase(rest.begin());
      }
    } else if (parseInteger(keyword, ignored)) {
      rest = tokens;
    } else {
      failAt("no OFF keyword and no counts (not an OFF file?)");
    }
    if (rest.empty() && !lines_.next(rest))
      fail(path_, "the file ends before the vertex and face counts");
    if (rest.size() < 2 || rest.size() > 3)
      failAt("expected the counts 'vertices faces edges', found " + std::to_string(rest.size()) +
             " values");
    vertexCount_ = count(rest[0], "vertex");
    faceCount_ = count(rest[1], "face");
    if (rest.size() == 3) count(rest[2], "edge");  // checked, otherwise unused
    const uint64_t needed = vertexCount_ * kMinVertexBytes + faceCount_ * kMinFaceBytes;
    // +1: the last line need not end in a newline.
    if (needed > lines_.remaining() + 1)
      failAt("the header announces " + std::to_string(vertexCount_) + " vertices and " +
             std::to_string(faceCount_) + " faces, more than the " +
             std::to_string(lines_.remaining()) + " bytes after it can hold (truncated?)");
  }

  // [ST][C][N][4][n] before "OFF"; true for "n" (the dimension follows).
  bool readPrefixes(std::string_view prefixes) {
    const std::string keyword = std::string(prefixes) + "OFF";
    if (prefixes.starts_with("ST")) prefixes.remove_prefix(2), prefixes_.uv = true;
    if (prefixes.starts_with("C")) prefixes.remove_prefix(1), prefixes_.color = true;
    if (prefixes.starts_with("N")) prefixes.remove_prefix(1), prefixes_.normal = true;
    if (prefixes.starts_with("4")) failAt("4-D OFF ('" + keyword + "') is not supported, only 3-D");
    const bool dimension = prefixes.starts_with("n");
    if (dimension) prefixes.remove_prefix(1);
    if (!prefixes.empty()) failAt("unknown keyword '" + keyword + "' (not an OFF file?)");
    return dimension;
  }

  uint64_t count(std::string_view token, const char* what) const {
    int64_t n = 0;
    if (!parseInteger(token, n))
      failAt(std::string(what) + " count '" + std::string(token) + "' is not an integer");
    if (n < 0) failAt(std::string(what) + " count " + std::to_string(n) + " is negative");
    if (n > kMaxCount)
      failAt(std::string(what) + " count " + std::to_string(n) + " is more than 2^31 - 1");
    return uint64_t(n);
  }

  double number(std::string_view token, const std::string& where, const char* what) const {
    double value = 0;
    if (!parseNumber(token, value))
      failAt(where + ": " + what + " '" + std::string(token) + "' is not a number");
    if (!std::isfinite(value))
      failAt(where + ": " + what + " is " + (std::isnan(value) ? "NaN" : "infinite"));
    // Stored as float: a value beyond its range would become infinite.
    if (!(std::abs(value) <= double(std::numeric_limits<float>::max())))
      failAt(where + ": " + what + " " + numberText(value) + " is beyond the float range");
    return value;
  }

  void readVertices(std::vector<std::string_view>& tokens) {
    FilePart& part = this->part();
    part.positions.resize(vertexCount_);
    if (prefixes_.normal) part.normals.resize(vertexCount_);
    if (prefixes_.uv) part.uvs.resize(vertexCount_);
    if (prefixes_.color) vertexColors_.resize(vertexCount_);
    const size_t fixed = 3 + (prefixes_.normal ? 3 : 0) + (prefixes_.uv ? 2 : 0);
    for (size_t v = 0; v < vertexCount_; ++v) {
      if (!lines_.next(tokens))
        fail(path_, "the file ends after " + std::to_string(v) + " of " +
                        std::to_string(vertexCount_) + " vertices (truncated?)");
      const std::string where = "vertex " + std::to_string(v);
      const size_t colors = tokens.size() - std::min(tokens.size(), fixed);
      const bool fits = prefixes_.color ? tokens.size() >= fixed && (colors == 3 || colors == 4)
                                        : tokens.size() == fixed;
      if (!fits)
        failAt(where + ": expected " + std::to_string(fixed) +
               (prefixes_.color ? " numbers and a colour of 3 or 4" : "") + " numbers, found " +
               std::to_string(tokens.size()));
      size_t k = 0;
      for (int a = 0; a < 3; ++a)
        part.positions[v][a] = float(number(tokens[k++], where, "coordinate"));
      if (prefixes_.normal)
        for (int a = 0; a < 3; ++a)
          part.normals[v][a] = float(number(tokens[k++], where, "normal"));
      if (prefixes_.color) {
        vertexColors_[v] = color(tokens, k, where);
        k += colors;
      }
      if (prefixes_.uv) {
        part.uvs[v].x = float(number(tokens[k], where, "texture coordinate"));
        part.uvs[v].y = float(number(tokens[k + 1], where, "texture coordinate"));
      }
    }
  }

  // A colour's red, green and blue from tokens[k...], as written; not negative.
  Vec3f color(const std::vector<std::string_view>& tokens, size_t k, const std::string& where) {
    Vec3f c;
    for (int a = 0; a < 3; ++a) {
      c[a] = float(number(tokens[k + size_t(a)], where, "colour"));
      if (c[a] < 0) failAt(where + ": colour " + numberText(c[a]) + " is negative");
    }
    return c;
  }

  void readFaces(std::vector<std::string_view>& tokens) {
    std::vector<uint32_t> polygon;
    FilePart& part = this->part();
    for (size_t f = 0; f < faceCount_; ++f) {
      if (!lines_.next(tokens))
        fail(path_, "the file ends after " + std::to_string(f) + " of " +
                        std::to_string(faceCount_) + " faces (truncated?)");
      const std::string where = "face " + std::to_string(f);
      int64_t corners = 0;
      if (!parseInteger(tokens[0], corners))
        failAt(where + ": corner count '" + std::string(tokens[0]) + "' is not an integer");
      if (corners < 0 || uint64_t(corners) > tokens.size() - 1)
        failAt(where + ": announces " + std::to_string(corners) + " corners, the line has " +
               std::to_string(tokens.size() - 1) + (tokens.size() == 2 ? " value" : " values") +
               " after it");
      polygon.clear();
      for (size_t k = 1; k <= size_t(corners); ++k) {
        int64_t index = -1;
        if (!parseInteger(tokens[k], index))
          failAt(where + ": vertex index '" + std::string(tokens[k]) + "' is not an integer");
        if (index < 0 || uint64_t(index) >= vertexCount_)
          failAt(where + ": vertex index " + std::to_string(index) + " is out of range (" +
                 std::to_string(vertexCount_) + " vertices)");
        polygon.push_back(uint32_t(index));
      }
      // What follows the corners: nothing, a colour-map index (Geomview's, ignored) or RGB(A).
      const size_t rest = tokens.size() - 1 - size_t(corners);
      if (rest == 3 || rest == 4) {
        faceColors_.resize(f, Vec3f(-1.0f));
        faceColors_.push_back(color(tokens, 1 + size_t(corners), where));
      } else if (rest == 1) {
        ++colorMapFaces_;
      } else if (rest != 0) {
        failAt(where + ": " + std::to_string(rest) +
               " values after the corners (expected none, a colour-map index or a colour of 3 "
               "or 4)");
      }
      if (polygon.size() < 3) ++contents_.droppedDegenerate;
      triangulatePolygon(part.positions, polygon, part.indices);
      triangleFaces_.resize(part.indices.size() / 3, uint32_t(f));
    }
    if (colorMapFaces_ > 0)
      contents_.warnings.push_back(std::to_string(colorMapFaces_) +
                                   " face colours given as colour-map indices ignored");
  }

  // 8-bit codes if any component is above 1, else fractions; sRGB to linear.
  static void decode(std::vector<Vec3f>& colors) {
    float scale = 1.0f;
    for (const Vec3f& c : colors)
      if (maxComponent(c) > 1.0f) scale = 255.0f;
    for (Vec3f& c : colors)
      if (c.x >= 0)  // -1: a face without a colour
        for (int a = 0; a < 3; ++a) c[a] = srgbToLinear(std::clamp(c[a] / scale, 0.0f, 1.0f));
  }

  void finishColors() {
    decode(vertexColors_);
    decode(faceColors_);
    FilePart& part = this->part();
    if (faceColors_.empty()) {
      part.colors = std::move(vertexColors_);
      return;
    }
    faceColors_.resize(faceCount_, Vec3f(-1.0f));
    // Face colours: every corner becomes a vertex of its own, coloured as its face (a face
    // without one keeps its vertices' colours, or white).
    FilePart split;
    const bool normals = !part.normals.empty(), uvs = !part.uvs.empty();
    split.positions.reserve(part.indices.size());
    split.colors.reserve(part.indices.size());
    split.indices.reserve(part.indices.size());
    for (size_t i = 0; i < part.indices.size(); ++i) {
      const uint32_t v = part.indices[i];
      const Vec3f face = faceColors_[triangleFaces_[i / 3]];
      split.indices.push_back(uint32_t(split.positions.size()));
      split.positions.push_back(part.positions[v]);
      if (normals) split.normals.push_back(part.normals[v]);
      if (uvs) split.uvs.push_back(part.uvs[v]);
      split.colors.push_back(face.x >= 0              ? face
                             : !vertexColors_.empty() ? vertexColors_[v]
                                                      : Vec3f(1.0f));
    }
    part = std::move(split);
  }

  FilePart& part() {
    if (contents_.parts.empty()) contents_.parts.emplace_back();
    return contents_.parts.front();
  }

  const std::string& path_;
  Lines lines_;
  Prefixes prefixes_;
  uint64_t vertexCount_ = 0, faceCount_ = 0;
  std::vector<Vec3f> vertexColors_;      // as written, until finishColors
  std::vector<Vec3f> faceColors_;        // as written; -1 for a face without one
  std::vector<uint32_t> triangleFaces_;  // the face of every triangle
  size_t colorMapFaces_ = 0;
  FileContents contents_;
};

}  // namespace

FileContents readOff(const std::string& path) {
  const std::string bytes = readFileBytes(path);
  return OffParser(path, bytes).parse();
}

}  // namespace parallax::meshio
