#include "parallax/importer/ply_format.h"

#include <algorithm>
#include <cctype>

namespace parallax::meshio {

bool parseType(std::string_view name, Type& type) {
  static const struct {
    std::string_view name;
    Type type;
  } kTypes[] = {{"char", Type::Int8},      {"int8", Type::Int8},       {"uchar", Type::UInt8},
                {"uint8", Type::UInt8},    {"short", Type::Int16},     {"int16", Type::Int16},
                {"ushort", Type::UInt16},  {"uint16", Type::UInt16},   {"int", Type::Int32},
                {"int32", Type::Int32},    {"uint", Type::UInt32},     {"uint32", Type::UInt32},
                {"float", Type::Float32},  {"float32", Type::Float32}, {"double", Type::Float64},
                {"float64", Type::Float64}};
  for (const auto& entry : kTypes)
    if (entry.name == name) {
      type = entry.type;
      return true;
    }
  return false;
}

size_t sizeOf(Type type) {
  switch (type) {
    case Type::Int8:
    case Type::UInt8:
      return 1;
    case Type::Int16:
    case Type::UInt16:
      return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32:
      return 4;
    case Type::Float64:
      return 8;
  }
  return 0;
}

bool isInteger(Type type) {
  return type != Type::Float32 && type != Type::Float64;
}

Header parsePlyHeader(const std::string& path, const std::string& bytes,
                      std::vector<std::string>& warnings) {
  Header header;
  size_t pos = 0, lineNumber = 0;
  bool sawFormat = false;
  auto headerError = [&](const std::string& message) {
    fail(path, "header line " + std::to_string(lineNumber) + ": " + message);
  };
  while (true) {
    if (pos >= bytes.size()) fail(path, "the header has no end_header line (not a PLY file?)");
    const size_t end = std::min(bytes.find('\n', pos), bytes.size());
    const std::string_view line(bytes.data() + pos, end - pos);
    pos = end + 1;
    ++lineNumber;
    TextTokens words(line);
    const std::string_view keyword = words.next();
    if (lineNumber == 1) {
      if (keyword != "ply" || !words.atEnd()) fail(path, "not a PLY file (no 'ply' first line)");
    } else if (keyword == "format") {
      const std::string_view name = words.next();
      if (name == "ascii")
        header.format = Format::Ascii;
      else if (name == "binary_little_endian")
        header.format = Format::BinaryLittleEndian;
      else if (name == "binary_big_endian")
        header.format = Format::BinaryBigEndian;
      else
        headerError("unknown format '" + std::string(name) + "'");
      sawFormat = true;
    } else if (keyword == "element") {
      Element element;
      element.name = std::string(words.next());
      int64_t count = -1;
      if (!parseInteger(words.next(), count) || count < 0)
        headerError("element '" + element.name + "' needs a count");
      element.count = uint64_t(count);
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) headerError("property before any element");
      Property property;
      std::string_view type = words.next();
      if (type == "list") {
        property.isList = true;
        if (!parseType(words.next(), property.countType) || !isInteger(property.countType))
          headerError("a list needs an integer count type");
        type = words.next();
      }
      if (!parseType(type, property.type))
        headerError("unknown property type '" + std::string(type) + "'");
      property.name = std::string(words.next());
      if (property.name.empty()) headerError("property without a name");
      header.elements.back().properties.push_back(std::move(property));
    } else if (keyword == "end_header") {
      break;
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      // Some exporters write a comment without the keyword; skip such lines, but say so.
      std::string text(line.substr(0, 40));
      while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
        text.pop_back();
      warnings.push_back("header line " + std::to_string(lineNumber) + ": ignored '" + text + "'");
    }
  }
  if (!sawFormat) fail(path, "the header has no format line");
  // "end_header" may be the file's last bytes, without a newline: no data follows.
  header.dataOffset = std::min(pos, bytes.size());
  header.dataLine = lineNumber + 1;
  return header;
}

void checkCountFits(const std::string& path, const Element& element, const ValueReader& values) {
  size_t binaryBytes = 0;
  for (const Property& p : element.properties)
    binaryBytes += sizeOf(p.isList ? p.countType : p.type);
  const size_t perItem = values.isText() ? 2 * element.properties.size() : binaryBytes;
  if (perItem > 0 && element.count > (values.remaining() + 1) / perItem)
    fail(path, "element '" + element.name + "' announces " + std::to_string(element.count) +
                   " items, more than the file can hold (truncated?)");
}

}  // namespace parallax::meshio
