// Building JSON output (reports, render.json, --json) without exposing the JSON library.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "parallax/core/math.h"

namespace parallax {

// Values are placed by JSON pointer; missing objects and arrays on the way are created
// ("/bounds/min" creates "bounds"; "/objects/0/name" creates an array).
class JsonWriter {
 public:
  JsonWriter();
  ~JsonWriter();
  JsonWriter(const JsonWriter&) = delete;
  JsonWriter& operator=(const JsonWriter&) = delete;

  void set(std::string_view pointer, double value);
  void set(std::string_view pointer, int64_t value);
  void set(std::string_view pointer, uint64_t value);
  void set(std::string_view pointer, int value) { set(pointer, int64_t(value)); }
  void set(std::string_view pointer, bool value);
  void set(std::string_view pointer, std::string_view value);
  void set(std::string_view pointer, const char* value) { set(pointer, std::string_view(value)); }
  void set(std::string_view pointer, const Vec3f& value);
  void set(std::string_view pointer, const std::vector<std::string>& values);
  // Sets the value to an empty array (so that an empty list still appears).
  void setEmptyArray(std::string_view pointer);

  std::string dump(int indent = 2) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace parallax
