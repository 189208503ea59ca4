// The PLY format (Greg Turk's, http://paulbourke.net/dataformats/ply/), internal to the
// importer: a text header declaring elements and their properties, then the data as ASCII or
// binary (little or big endian). Its two readers share it: meshes (mesh_ply.cpp) and Gaussian
// splats (splat_ply.cpp), told apart by the vertex element's properties.
#pragma once

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "parallax/importer/mesh_reading.h"

namespace parallax::meshio {

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };
enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct Property {
  std::string name;
  Type type = Type::Float32;
  bool isList = false;
  Type countType = Type::UInt8;  // list properties: type of the length that precedes them
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  size_t dataOffset = 0;  // first byte after "end_header\n"
  size_t dataLine = 0;    // line number of the first data line (ASCII messages)
};

bool parseType(std::string_view name, Type& type);
size_t sizeOf(Type type);
bool isInteger(Type type);
// The header of `bytes` (the whole file), up to and including end_header; lines it does not
// know become warnings. Throws InputError naming `path` and the header line.
Header parsePlyHeader(const std::string& path, const std::string& bytes,
                      std::vector<std::string>& warnings);

// Reads the values that follow the header, one at a time, in either encoding.
class ValueReader {
 public:
  ValueReader(const std::string& path, const std::string& bytes, const Header& header)
      : path_(path),
        bytes_(bytes),
        format_(header.format),
        pos_(header.dataOffset),
        tokens_(std::string_view(bytes).substr(header.dataOffset), header.dataLine) {}

  // `where` describes the item being read, for messages ("vertex 12").
  double read(Type type, const std::string& where) {
    if (format_ == Format::Ascii) return readText(type, where);
    const size_t size = sizeOf(type);
    if (bytes_.size() - pos_ < size)
      fail(path_, where + ": the file ends inside the data (truncated)");
    // Assemble the value's bits from the bytes in file order, independent of the host's.
    const auto* raw = reinterpret_cast<const unsigned char*>(bytes_.data() + pos_);
    pos_ += size;
    uint64_t bits = 0;
    for (size_t i = 0; i < size; ++i) {
      const size_t significance = format_ == Format::BinaryLittleEndian ? i : size - 1 - i;
      bits |= uint64_t(raw[i]) << (8 * significance);
    }
    return decode(type, bits);
  }

  // A binary value's bits (assembled in the file's byte order) as the number they encode.
  static double decode(Type type, uint64_t bits) {
    switch (type) {
      case Type::Int8:
        return double(int8_t(uint8_t(bits)));
      case Type::UInt8:
        return double(uint8_t(bits));
      case Type::Int16:
        return double(int16_t(uint16_t(bits)));
      case Type::UInt16:
        return double(uint16_t(bits));
      case Type::Int32:
        return double(int32_t(uint32_t(bits)));
      case Type::UInt32:
        return double(uint32_t(bits));
      case Type::Float32:
        return double(std::bit_cast<float>(uint32_t(bits)));
      case Type::Float64:
        return std::bit_cast<double>(bits);
    }
    return 0;
  }

  // Bytes not yet read (for ASCII: all data bytes), to reject absurd element counts before
  // allocating for them.
  size_t remaining() const { return bytes_.size() - pos_; }
  bool isText() const { return format_ == Format::Ascii; }

 private:
  double readText(Type type, const std::string& where) {
    const std::string_view token = tokens_.next();
    if (token.empty()) fail(path_, where + ": the file ends inside the data (truncated)");
    // The message is built only on failure: this runs once per number of the file.
    auto at = [&] { return "line " + std::to_string(tokens_.line()) + ": " + where + ": "; };
    if (isInteger(type)) {
      int64_t value = 0;
      if (!parseInteger(token, value))
        fail(path_, at() + "expected an integer, found '" + std::string(token) + "'");
      return double(value);
    }
    double value = 0;
    if (!parseNumber(token, value))
      fail(path_, at() + "expected a number, found '" + std::string(token) + "'");
    return value;
  }

  const std::string& path_;
  const std::string& bytes_;
  Format format_;
  size_t pos_;
  TextTokens tokens_;
};

// An item needs, in binary, the bytes of its scalars and list lengths; in ASCII, at least one
// character and one separator per value. A count that cannot fit in what is left of the file is
// truncation, refused (naming the element) before any memory is reserved for it.
void checkCountFits(const std::string& path, const Element& element, const ValueReader& values);

}  // namespace parallax::meshio
