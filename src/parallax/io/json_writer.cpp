#include "parallax/io/json_writer.h"

#include <nlohmann/json.hpp>

namespace parallax {

struct JsonWriter::Impl {
  nlohmann::json root = nlohmann::json::object();
  nlohmann::json& at(std::string_view pointer) {
    return root[nlohmann::json::json_pointer(std::string(pointer))];
  }
};

JsonWriter::JsonWriter() : impl_(std::make_unique<Impl>()) {}
JsonWriter::~JsonWriter() = default;

void JsonWriter::set(std::string_view p, double v) {
  impl_->at(p) = v;
}
void JsonWriter::set(std::string_view p, int64_t v) {
  impl_->at(p) = v;
}
void JsonWriter::set(std::string_view p, uint64_t v) {
  impl_->at(p) = v;
}
void JsonWriter::set(std::string_view p, bool v) {
  impl_->at(p) = v;
}
void JsonWriter::set(std::string_view p, std::string_view v) {
  impl_->at(p) = std::string(v);
}
void JsonWriter::set(std::string_view p, const Vec3f& v) {
  impl_->at(p) = nlohmann::json::array({v.x, v.y, v.z});
}
void JsonWriter::set(std::string_view p, const std::vector<std::string>& v) {
  impl_->at(p) = v;
}
void JsonWriter::setEmptyArray(std::string_view p) {
  impl_->at(p) = nlohmann::json::array();
}

std::string JsonWriter::dump(int indent) const {
  return impl_->root.dump(indent);
}

}  // namespace parallax
