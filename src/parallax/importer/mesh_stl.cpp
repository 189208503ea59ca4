// STL reader, binary and ASCII. Binary STL is an 80-byte header, a little-endian uint32
// triangle count and one 50-byte record per triangle (normal, three vertices as 12 floats,
// a 2-byte attribute). ASCII STL is "solid name / facet normal n n n / outer loop / vertex x
// y z (x3) / endloop / endfacet / ... / endsolid name". Some binary files also begin with
// "solid", so the size check decides: a file whose size matches its triangle count is binary.
// Facet normals are ignored (they are often wrong); the renderer uses the geometric normal.
#include <bit>
#include <cstring>

#include "parallax/core/error.h"
#include "parallax/importer/mesh_readers.h"

namespace parallax::meshio {
namespace {

constexpr size_t kHeaderBytes = 84;
constexpr size_t kRecordBytes = 50;

uint32_t readU32LE(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

float readF32LE(const unsigned char* p) {
  return std::bit_cast<float>(readU32LE(p));
}

void readBinary(const std::string& bytes, uint32_t count, FilePart& part) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  part.positions.reserve(size_t(count) * 3);
  part.indices.reserve(size_t(count) * 3);
  for (size_t t = 0; t < count; ++t) {
    const unsigned char* vertices = data + kHeaderBytes + t * kRecordBytes + 12;
    for (int corner = 0; corner < 3; ++corner) {
      const unsigned char* v = vertices + 12 * corner;
      part.indices.push_back(uint32_t(part.positions.size()));
      part.positions.push_back({readF32LE(v), readF32LE(v + 4), readF32LE(v + 8)});
    }
  }
}

class AsciiStlParser {
 public:
  AsciiStlParser(const std::string& path, const std::string& text, FilePart& part)
      : path_(path), tokens_(text), part_(part) {}

  void parse() {
    do {
      expect("solid");
      tokens_.skipLine();  // the solid's name
      for (std::string_view word = tokens_.next(); word != "endsolid"; word = tokens_.next()) {
        if (word != "facet") error("expected 'facet' or 'endsolid'", word);
        readFacet();
      }
      tokens_.skipLine();
    } while (!tokens_.atEnd());
  }

 private:
  void readFacet() {
    expect("normal");
    for (int i = 0; i < 3; ++i) number();
    expect("outer");
    expect("loop");
    std::vector<uint32_t> corners;
    for (std::string_view word = tokens_.next(); word != "endloop"; word = tokens_.next()) {
      if (word != "vertex") error("expected 'vertex' or 'endloop'", word);
      Vec3f p;
      for (int axis = 0; axis < 3; ++axis) p[axis] = float(number());
      corners.push_back(uint32_t(part_.positions.size()));
      part_.positions.push_back(p);
    }
    // STL facets are triangles; a longer loop is split like a polygon, a shorter one dropped.
    triangulatePolygon(part_.positions, corners, part_.indices);
    if (corners.size() < 3) ++droppedFacets;
    expect("endfacet");
  }

  double number() {
    const std::string_view token = tokens_.next();
    double value = 0;
    if (!parseNumber(token, value)) error("expected a number", token);
    return value;
  }

  void expect(std::string_view keyword) {
    const std::string_view token = tokens_.next();
    if (token != keyword) error("expected '" + std::string(keyword) + "'", token);
  }

  [[noreturn]] void error(const std::string& what, std::string_view found) {
    const std::string got =
        found.empty() ? "the file ends (truncated?)" : "found '" + std::string(found) + "'";
    fail(path_, "line " + std::to_string(tokens_.line()) + ": " + what + ", " + got);
  }

  const std::string& path_;
  TextTokens tokens_;
  FilePart& part_;

 public:
  size_t droppedFacets = 0;
};

bool startsWithSolid(const std::string& bytes) {
  const size_t start = bytes.find_first_not_of(" \t\r\n");
  return start != std::string::npos && bytes.compare(start, 5, "solid") == 0;
}

}  // namespace

FileContents readStl(const std::string& path) {
  const std::string bytes = readFileBytes(path);
  FileContents contents;
  FilePart& part = contents.parts.emplace_back();

  std::string binaryProblem;
  if (bytes.size() >= kHeaderBytes) {
    const uint32_t count = readU32LE(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
    const uint64_t expected = kHeaderBytes + uint64_t(count) * kRecordBytes;
    if (bytes.size() == expected) {
      readBinary(bytes, count, part);
      return contents;
    }
    binaryProblem = "as binary STL, the header announces " + std::to_string(count) +
                    " triangles (" + std::to_string(expected) + " bytes) but the file has " +
                    std::to_string(bytes.size()) + " bytes (truncated?)";
  } else {
    binaryProblem = "too short for a binary STL (" + std::to_string(bytes.size()) +
                    " bytes, the header alone is 84)";
  }
  if (!startsWithSolid(bytes)) fail(path, binaryProblem);

  AsciiStlParser parser(path, bytes, part);
  try {
    parser.parse();
  } catch (const InputError& asciiError) {
    // A binary file whose header starts with "solid" lands here too: report both readings.
    if (bytes.find('\0') == std::string::npos) throw;
    fail(path, binaryProblem + "; as ASCII STL: " + asciiError.what());
  }
  contents.droppedDegenerate = parser.droppedFacets;
  return contents;
}

}  // namespace parallax::meshio
