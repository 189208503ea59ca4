// A typed, read-only view of a parsed JSON document in which every node knows its JSON pointer
// (RFC 6901) and file, so that every complaint about the input names exactly where it is:
//   InputError("scene.json", "/objects/3/material/color", "expected 3 numbers ...")
// The JSON library stays inside json_reader.cpp.
#pragma once

#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "parallax/core/math.h"

namespace parallax {

class JsonReader;

// Arrays and objects nested deeper than this are refused while parsing (a deep file would
// otherwise exhaust the stack of whatever walks it).
inline constexpr size_t kMaxJsonDepth = 256;

// A parsed document. Comments (// and /* */) are allowed; duplicate keys are rejected. Keys
// keep the order of the file, so errors and named entries come out in the author's order.
class JsonDocument {
 public:
  // Throw InputError for a missing, unreadable or non-regular file (a folder, a device, a
  // FIFO), for malformed JSON (with the line and column of the problem), for nesting deeper
  // than kMaxJsonDepth and for a number beyond double range (at its JSON pointer). `file`
  // only names the text in errors.
  static JsonDocument parseFile(const std::string& path);
  static JsonDocument parseText(const std::string& text, const std::string& file);

  JsonDocument(JsonDocument&&) noexcept;
  JsonDocument& operator=(JsonDocument&&) noexcept;
  ~JsonDocument();

  // The whole document; valid while this JsonDocument lives.
  JsonReader root() const;

 private:
  struct Impl;
  explicit JsonDocument(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

class JsonReader {
 public:
  const std::string& file() const { return *file_; }
  const std::string& pointer() const { return pointer_; }
  [[noreturn]] void fail(const std::string& message) const;

  bool isObject() const;
  bool isArray() const;
  bool isString() const;
  bool isNumber() const;
  // Members of an object or elements of an array; 0 for other values.
  size_t size() const;
  // Compact JSON text of the value and a description of its type ("an array"), for messages.
  std::string dump() const;
  std::string typeName() const;

  // Objects. expectObject checks that this is an object whose keys are all in `allowedKeys`;
  // an unknown key fails at its own pointer with a "did you mean" hint.
  void expectObject(std::initializer_list<std::string_view> allowedKeys) const;
  void expectObject(const std::vector<std::string>& allowedKeys) const;
  bool has(std::string_view key) const;
  // A member that must be present ("missing key 'radius'").
  JsonReader operator[](std::string_view key) const;
  std::optional<JsonReader> find(std::string_view key) const;
  // Every member of an object, in file order.
  std::vector<std::pair<std::string, JsonReader>> members() const;

  // Arrays (fails if this is not an array).
  std::vector<JsonReader> elements() const;

  // Values; each fails with "expected ..." when the type or range is wrong. Every float
  // result is finite as a float (a number beyond 3.4e38 fails rather than becoming inf), and
  // a positive float is not rounded to 0.
  std::string string() const;
  bool boolean() const;
  double number() const;                               // finite
  double number(double lowest, double highest) const;  // in [lowest, highest]
  float real() const;                                  // finite in float
  float positive() const;
  float nonNegative() const;
  int integer(int lowest, int highest) const;
  Vec3f vec3() const;       // [x, y, z], finite in float
  Vec3f direction() const;  // a non-zero [x, y, z], normalised
  // A linear RGB colour: [r, g, b] or one number for grey, every channel >= 0.
  Vec3f color() const;

  // Optional members with a default when absent.
  std::string string(std::string_view key, const std::string& fallback) const;
  bool boolean(std::string_view key, bool fallback) const;
  float positive(std::string_view key, float fallback) const;
  int integer(std::string_view key, int fallback, int lowest, int highest) const;
  Vec3f vec3(std::string_view key, const Vec3f& fallback) const;
  Vec3f direction(std::string_view key, const Vec3f& fallback) const;
  Vec3f color(std::string_view key, const Vec3f& fallback) const;

 private:
  friend class JsonDocument;
  // `node` is a node of the JSON library's document (opaque here to keep the library private).
  JsonReader(const void* node, std::shared_ptr<const std::string> file, std::string pointer)
      : node_(node), file_(std::move(file)), pointer_(std::move(pointer)) {}
  JsonReader child(const void* node, std::string_view token) const;
  void expectObjectType() const;

  const void* node_;
  std::shared_ptr<const std::string> file_;
  std::string pointer_;
};

// The closest candidate within a small edit distance, for "did you mean" hints, or "".
std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace parallax
