#include "parallax/io/json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <unordered_set>

#include <nlohmann/json.hpp>

#include "parallax/io/input_file.h"

namespace parallax {
namespace {

using Json = nlohmann::ordered_json;

const Json& asJson(const void* node) {
  return *static_cast<const Json*>(node);
}

// RFC 6901: "~" and "/" inside a key are written "~0" and "~1".
std::string escapePointerToken(std::string_view token) {
  std::string out;
  for (char c : token) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

// Tracks where the parser is so that a duplicate key, a too deep nesting or a number out of
// range can be reported at its JSON pointer. nlohmann calls the callback with
// object_start/array_start before a container, key before each member and value after each
// scalar.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(const std::string& file) : file_(file) {}

  bool operator()(int /*depth*/, nlohmann::detail::parse_event_t event, Json& parsed) {
    using Event = nlohmann::detail::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        countArrayElement();
        if (frames_.size() >= kMaxJsonDepth)
          throw inputError(file_, pointer(),
                           "nested more than " + std::to_string(kMaxJsonDepth) +
                               " levels deep (arrays and objects inside each other)");
        frames_.push_back({event == Event::array_start, -1, "", {}});
        break;
      case Event::key: {
        Frame& top = frames_.back();
        top.key = parsed.get<std::string>();
        if (!top.keys.insert(top.key).second)
          throw inputError(file_, pointer(), "duplicate key '" + top.key + "'");
        break;
      }
      case Event::value:
        countArrayElement();
        break;
      case Event::object_end:
      case Event::array_end:
        frames_.pop_back();
        break;
    }
    return true;
  }

  // Where the value being parsed goes: the last key of an object, the next index of an array.
  std::string pendingPointer() const {
    std::string p;
    for (size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      const bool last = i + 1 == frames_.size();
      p += "/" + (f.isArray ? std::to_string(f.index + (last ? 1 : 0)) : escapePointerToken(f.key));
    }
    return p;
  }

 private:
  struct Frame {
    bool isArray;
    int index;
    std::string key;
    std::unordered_set<std::string> keys;
  };
  void countArrayElement() {
    if (!frames_.empty() && frames_.back().isArray) ++frames_.back().index;
  }
  std::string pointer() const {
    std::string p;
    for (const Frame& f : frames_)
      p += "/" + (f.isArray ? std::to_string(f.index) : escapePointerToken(f.key));
    return p;
  }
  const std::string& file_;
  std::vector<Frame> frames_;
};

// nlohmann's messages start with "[json.exception.parse_error.101] "; keep the rest, which
// already says "parse error at line L, column C: ...".
std::string parseErrorMessage(const std::string& what) {
  const size_t close = what.find("] ");
  return close == std::string::npos ? what : what.substr(close + 2);
}

size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// Compact JSON text for a message, cut short (a value may be a megabyte of numbers).
std::string shortDump(const Json& value) {
  constexpr size_t kMaxChars = 60;
  std::string text =
      value.dump(-1, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::replace);
  if (text.size() > kMaxChars) text = text.substr(0, kMaxChars - 3) + "...";
  return text;
}

std::string describeJsonType(const Json& value) {
  if (value.is_object()) return "an object";
  if (value.is_array()) return "an array";
  if (value.is_string()) return "a string";
  if (value.is_boolean()) return "true/false";
  if (value.is_null()) return "null";
  return "a number";
}

}  // namespace

struct JsonDocument::Impl {
  Json json;
  std::shared_ptr<const std::string> file;
};

JsonDocument::JsonDocument(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
JsonDocument::JsonDocument(JsonDocument&&) noexcept = default;
JsonDocument& JsonDocument::operator=(JsonDocument&&) noexcept = default;
JsonDocument::~JsonDocument() = default;

JsonDocument JsonDocument::parseText(const std::string& text, const std::string& file) {
  auto impl = std::make_unique<Impl>();
  impl->file = std::make_shared<const std::string>(file);
  DuplicateKeyCheck check(file);
  const std::function<bool(int, nlohmann::detail::parse_event_t, Json&)> callback =
      [&check](int depth, nlohmann::detail::parse_event_t event, Json& parsed) {
        return check(depth, event, parsed);
      };
  try {
    impl->json = Json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::parse_error& e) {
    throw inputError(file, "", "invalid JSON: " + parseErrorMessage(e.what()));
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond double range (1e400): nlohmann says "number overflow parsing '1e400'".
    throw inputError(file, check.pendingPointer(),
                     "number out of range (" + parseErrorMessage(e.what()) + ")");
  } catch (const nlohmann::json::exception& e) {
    throw inputError(file, check.pendingPointer(), "invalid JSON: " + parseErrorMessage(e.what()));
  }
  return JsonDocument(std::move(impl));
}

JsonDocument JsonDocument::parseFile(const std::string& path) {
  return parseText(readInputFile(path), path);
}

JsonReader JsonDocument::root() const {
  return JsonReader(&impl_->json, impl_->file, "");
}

std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t bestDistance = std::max<size_t>(2, word.size() / 3) + 1;
  for (const std::string& candidate : candidates) {
    const size_t d = editDistance(word, candidate);
    if (d < bestDistance) {
      bestDistance = d;
      best = candidate;
    }
  }
  return best;
}

void JsonReader::fail(const std::string& message) const {
  throw inputError(*file_, pointer_, message);
}

JsonReader JsonReader::child(const void* node, std::string_view token) const {
  return JsonReader(node, file_, pointer_ + "/" + escapePointerToken(token));
}

bool JsonReader::isObject() const {
  return asJson(node_).is_object();
}
bool JsonReader::isArray() const {
  return asJson(node_).is_array();
}
bool JsonReader::isString() const {
  return asJson(node_).is_string();
}
bool JsonReader::isNumber() const {
  return asJson(node_).is_number();
}
size_t JsonReader::size() const {
  return asJson(node_).is_structured() ? asJson(node_).size() : 0;
}
std::string JsonReader::dump() const {
  return shortDump(asJson(node_));
}
std::string JsonReader::typeName() const {
  return describeJsonType(asJson(node_));
}

void JsonReader::expectObjectType() const {
  if (!asJson(node_).is_object())
    fail("expected an object, found " + describeJsonType(asJson(node_)));
}

void JsonReader::expectObject(std::initializer_list<std::string_view> allowedKeys) const {
  expectObject(std::vector<std::string>(allowedKeys.begin(), allowedKeys.end()));
}

void JsonReader::expectObject(const std::vector<std::string>& allowedKeys) const {
  expectObjectType();
  for (const auto& [key, value] : asJson(node_).items()) {
    if (std::find(allowedKeys.begin(), allowedKeys.end(), key) != allowedKeys.end()) continue;
    const std::string suggestion = closestMatch(key, allowedKeys);
    child(&value, key)
        .fail(suggestion.empty() ? "unknown key"
                                 : "unknown key (did you mean '" + suggestion + "'?)");
  }
}

bool JsonReader::has(std::string_view key) const {
  return asJson(node_).is_object() && asJson(node_).contains(std::string(key));
}

JsonReader JsonReader::operator[](std::string_view key) const {
  expectObjectType();
  const auto it = asJson(node_).find(std::string(key));
  if (it == asJson(node_).end()) fail("missing key '" + std::string(key) + "'");
  return child(&*it, key);
}

std::optional<JsonReader> JsonReader::find(std::string_view key) const {
  expectObjectType();
  const auto it = asJson(node_).find(std::string(key));
  if (it == asJson(node_).end()) return std::nullopt;
  return child(&*it, key);
}

std::vector<std::pair<std::string, JsonReader>> JsonReader::members() const {
  expectObjectType();
  std::vector<std::pair<std::string, JsonReader>> out;
  for (const auto& [key, value] : asJson(node_).items()) out.emplace_back(key, child(&value, key));
  return out;
}

std::vector<JsonReader> JsonReader::elements() const {
  if (!asJson(node_).is_array())
    fail("expected an array, found " + describeJsonType(asJson(node_)));
  std::vector<JsonReader> out;
  for (size_t i = 0; i < asJson(node_).size(); ++i)
    out.push_back(child(&asJson(node_)[i], std::to_string(i)));
  return out;
}

std::string JsonReader::string() const {
  if (!asJson(node_).is_string())
    fail("expected a string, found " + describeJsonType(asJson(node_)));
  return asJson(node_).get<std::string>();
}

bool JsonReader::boolean() const {
  if (!asJson(node_).is_boolean())
    fail("expected true or false, found " + describeJsonType(asJson(node_)));
  return asJson(node_).get<bool>();
}

double JsonReader::number() const {
  if (!asJson(node_).is_number())
    fail("expected a number, found " + describeJsonType(asJson(node_)));
  const double v = asJson(node_).get<double>();
  if (!std::isfinite(v)) fail("expected a finite number");
  return v;
}

namespace {
std::string shortNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}
}  // namespace

double JsonReader::number(double lowest, double highest) const {
  const double v = number();
  if (!(v >= lowest && v <= highest))
    fail("expected a number from " + shortNumber(lowest) + " to " + shortNumber(highest) +
         ", found " + shortDump(asJson(node_)));
  return v;
}

float JsonReader::real() const {
  const double v = number();
  if (!(std::abs(v) <= double(std::numeric_limits<float>::max())))
    fail("number too large (beyond the float range, about 3.4e38), found " +
         shortDump(asJson(node_)));
  return float(v);
}

float JsonReader::positive() const {
  const float v = real();
  if (!(v > 0)) fail("expected a positive number, found " + shortDump(asJson(node_)));
  return v;
}

float JsonReader::nonNegative() const {
  const float v = real();
  if (v < 0) fail("expected a number >= 0, found " + shortDump(asJson(node_)));
  return v;
}

int JsonReader::integer(int lowest, int highest) const {
  if (!asJson(node_).is_number_integer() || asJson(node_).get<double>() < lowest ||
      asJson(node_).get<double>() > highest)
    fail("expected an integer from " + std::to_string(lowest) + " to " + std::to_string(highest) +
         ", found " + shortDump(asJson(node_)));
  return asJson(node_).get<int>();
}

Vec3f JsonReader::vec3() const {
  if (!asJson(node_).is_array() || asJson(node_).size() != 3 ||
      !std::all_of(asJson(node_).begin(), asJson(node_).end(),
                   [](const Json& v) { return v.is_number(); }))
    fail("expected 3 numbers [x, y, z], found " + shortDump(asJson(node_)));
  const auto e = elements();
  return {e[0].real(), e[1].real(), e[2].real()};
}

Vec3f JsonReader::direction() const {
  const Vec3f v = vec3();
  // In double: the squares of large floats would overflow.
  const double len = std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
  if (!(len > 0)) fail("expected a non-zero direction");
  return {float(v.x / len), float(v.y / len), float(v.z / len)};
}

Vec3f JsonReader::color() const {
  const bool grey = asJson(node_).is_number();
  const bool rgb = asJson(node_).is_array() && asJson(node_).size() == 3 &&
                   std::all_of(asJson(node_).begin(), asJson(node_).end(),
                               [](const Json& v) { return v.is_number(); });
  if (!grey && !rgb)
    fail("expected 3 numbers [r, g, b] or one number for grey, found " + shortDump(asJson(node_)));
  if (grey) return Vec3f(nonNegative());
  const auto e = elements();
  return {e[0].nonNegative(), e[1].nonNegative(), e[2].nonNegative()};
}

std::string JsonReader::string(std::string_view key, const std::string& fallback) const {
  const auto v = find(key);
  return v ? v->string() : fallback;
}

bool JsonReader::boolean(std::string_view key, bool fallback) const {
  const auto v = find(key);
  return v ? v->boolean() : fallback;
}

float JsonReader::positive(std::string_view key, float fallback) const {
  const auto v = find(key);
  return v ? v->positive() : fallback;
}

int JsonReader::integer(std::string_view key, int fallback, int lowest, int highest) const {
  const auto v = find(key);
  return v ? v->integer(lowest, highest) : fallback;
}

Vec3f JsonReader::vec3(std::string_view key, const Vec3f& fallback) const {
  const auto v = find(key);
  return v ? v->vec3() : fallback;
}

Vec3f JsonReader::direction(std::string_view key, const Vec3f& fallback) const {
  const auto v = find(key);
  return v ? v->direction() : fallback;
}

Vec3f JsonReader::color(std::string_view key, const Vec3f& fallback) const {
  const auto v = find(key);
  return v ? v->color() : fallback;
}

}  // namespace parallax
