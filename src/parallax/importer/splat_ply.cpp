#include "parallax/importer/splat_ply.h"

#include "parallax/core/error.h"
#include "parallax/core/parallel.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace parallax::meshio {

namespace {

// A log scale beyond this is no Gaussian of a capture (exp(30) = 1e13).
constexpr double kMaxLogScale = 30.0;

const Element* vertexElement(const Header& header) {
  for (const Element& e : header.elements)
    if (e.name == "vertex") return &e;
  return nullptr;
}

int propertyIndex(const Element& element, const std::string& name) {
  for (size_t i = 0; i < element.properties.size(); ++i)
    if (element.properties[i].name == name) return int(i);
  return -1;
}

// Where each field of a splat is among the vertex's properties.
struct SplatLayout {
  int position[3], dc[3], opacity, scale[3], rotation[4];
  std::vector<int> rest;  // f_rest_0.. in order
  int degree = 0;

  SplatLayout(const std::string& path, const Element& vertex) {
    const auto required = [&](const std::string& name) {
      const int i = propertyIndex(vertex, name);
      if (i < 0) fail(path, "the splats' vertex element lacks the property " + name);
      if (vertex.properties[size_t(i)].isList) fail(path, "property " + name + " is a list");
      return i;
    };
    for (int c = 0; c < 3; ++c) {
      position[c] = required(std::string(1, "xyz"[c]));
      dc[c] = required("f_dc_" + std::to_string(c));
      scale[c] = required("scale_" + std::to_string(c));
    }
    opacity = required("opacity");
    for (int c = 0; c < 4; ++c) rotation[c] = required("rot_" + std::to_string(c));
    for (int k = 0;; ++k) {
      const int i = propertyIndex(vertex, "f_rest_" + std::to_string(k));
      if (i < 0) break;
      if (vertex.properties[size_t(i)].isList)
        fail(path, "property f_rest_" + std::to_string(k) + " is a list");
      rest.push_back(i);
    }
    // 3 channels of (degree + 1)^2 - 1 coefficients: 0, 9, 24 or 45.
    while (degree <= kMaxShDegree && size_t(3 * (shCoefficientCount(degree) - 1)) < rest.size())
      ++degree;
    if (degree > kMaxShDegree || size_t(3 * (shCoefficientCount(degree) - 1)) != rest.size())
      fail(path, "f_rest_0.." + std::to_string(rest.size() - 1) + ": " +
                     std::to_string(rest.size()) +
                     " coefficients are no degree's (0, 9, 24 or 45: degrees 0 to 3)");
  }
};

std::string splatName(uint64_t g) {
  return "splat " + std::to_string(g);
}

// Splat `item` from its record of property values (in the vertex element's order) into the
// cloud, which has room for it: the encodings undone, every field checked in one fixed order,
// so that both readers name the same field of the same splat.
void decodeSplat(const std::string& path, const Element& vertex, const SplatLayout& layout,
                 const double* record, uint64_t item, GaussianCloud& cloud) {
  const size_t coefficients = size_t(shCoefficientCount(layout.degree));
  const auto field = [&](int index) {
    const double value = record[size_t(index)];
    if (!std::isfinite(value))
      fail(path, splatName(item) + ": " + vertex.properties[size_t(index)].name +
                     " is not a finite number");
    return value;
  };
  Vec3f centre, scale;
  for (int c = 0; c < 3; ++c) {
    centre[c] = float(field(layout.position[c]));
    const double logScale = field(layout.scale[c]);
    if (std::abs(logScale) > kMaxLogScale)
      fail(path, splatName(item) + ": scale_" + std::to_string(c) + " is " +
                     std::to_string(logScale) +
                     ", a log scale beyond +-30 (a size of e^30 = 1e13 or its inverse)");
    scale[c] = float(std::exp(logScale));
  }
  const Quatf rotation{float(field(layout.rotation[0])), float(field(layout.rotation[1])),
                       float(field(layout.rotation[2])), float(field(layout.rotation[3]))};
  if (rotation.w == 0 && rotation.x == 0 && rotation.y == 0 && rotation.z == 0)
    fail(path, splatName(item) + ": rot_0..3 is the zero quaternion (no rotation)");
  cloud.centres[item] = centre;
  cloud.scales[item] = scale;
  cloud.rotations[item] = rotation;
  cloud.opacities[item] = float(1.0 / (1.0 + std::exp(-field(layout.opacity))));
  Vec3f sh[shCoefficientCount(kMaxShDegree)];
  for (int c = 0; c < 3; ++c) {
    sh[0][c] = float(field(layout.dc[c]));
    // f_rest is channel-major: channel c's coefficients 1.. are f_rest_{c (K - 1) + k - 1}.
    for (size_t k = 1; k < coefficients; ++k)
      sh[k][c] = float(field(layout.rest[size_t(c) * (coefficients - 1) + k - 1]));
  }
  for (size_t k = 0; k < coefficients; ++k) cloud.sh.set(item * coefficients + k, sh[k]);
}

}  // namespace

bool holdsSplats(const Header& header) {
  const Element* vertex = vertexElement(header);
  return vertex && propertyIndex(*vertex, "opacity") >= 0 &&
         propertyIndex(*vertex, "scale_0") >= 0 && propertyIndex(*vertex, "rot_0") >= 0;
}

GaussianCloud readSplats(const std::string& path, const std::string& bytes, const Header& header) {
  const Element& vertex = *vertexElement(header);
  const SplatLayout layout(path, vertex);
  ValueReader values(path, bytes, header);
  // Elements before the vertex element are read past; the splats are the vertices.
  std::vector<double> record(vertex.properties.size());
  GaussianCloud cloud;
  cloud.shDegree = layout.degree;
  const size_t coefficients = size_t(shCoefficientCount(layout.degree));
  for (const Element& element : header.elements) {
    checkCountFits(path, element, values);
    // Each element's own record: another element (even one also called "vertex") may have more
    // properties than the splats' (a fuzzer's find: the record was the splats' size).
    record.assign(element.properties.size(), 0.0);
    const bool splats = &element == &vertex;
    if (splats) {
      cloud.centres.resize(element.count);
      cloud.scales.resize(element.count);
      cloud.rotations.resize(element.count);
      cloud.opacities.resize(element.count);
      cloud.sh.resize(element.count * coefficients);
    }
    for (uint64_t item = 0; item < element.count; ++item) {
      const std::string where = element.name + " " + std::to_string(item);
      for (size_t i = 0; i < element.properties.size(); ++i) {
        const Property& p = element.properties[i];
        if (p.isList) {
          const double n = values.read(p.countType, where);
          if (!(n >= 0) || n > double(values.remaining()))
            fail(path, where + ": list '" + p.name + "' has an impossible length");
          for (size_t k = 0; k < size_t(n); ++k) values.read(p.type, where);
        } else {
          record[i] = values.read(p.type, where);
        }
      }
      if (!splats) continue;
      decodeSplat(path, vertex, layout, record.data(), item, cloud);
    }
  }
  return cloud;
}

std::optional<GaussianCloud> readSplatsInBlocks(const std::string& path,
                                                std::vector<std::string>& warnings) {
  std::ifstream in(path, std::ios::binary);
  std::error_code error;
  const uintmax_t size = std::filesystem::file_size(path, error);
  if (!in || error) return std::nullopt;  // the whole-file reader says what is wrong
  constexpr uintmax_t kHeaderBytes = 4 << 20;
  std::string prefix(size_t(std::min(size, kHeaderBytes)), '\0');
  in.read(prefix.data(), std::streamsize(prefix.size()));
  if (size_t(in.gcount()) != prefix.size() || prefix.find("end_header") == std::string::npos)
    return std::nullopt;
  std::vector<std::string> headerWarnings;
  const Header header = parsePlyHeader(path, prefix, headerWarnings);
  if (!holdsSplats(header) || header.format == Format::Ascii) return std::nullopt;
  for (const Element& element : header.elements)
    for (const Property& p : element.properties)
      if (p.isList) return std::nullopt;
  warnings.insert(warnings.end(), headerWarnings.begin(), headerWarnings.end());
  const Element& vertex = *vertexElement(header);
  const SplatLayout layout(path, vertex);
  const bool little = header.format == Format::BinaryLittleEndian;
  GaussianCloud cloud;
  cloud.shDegree = layout.degree;
  uint64_t pos = header.dataOffset, remaining = size - std::min<uint64_t>(size, pos);
  for (const Element& element : header.elements) {
    std::vector<size_t> offsets;
    size_t stride = 0;
    for (const Property& p : element.properties)
      offsets.push_back(stride), stride += sizeOf(p.type);
    // As checkCountFits and ValueReader do for the whole-file reader, with the same messages.
    if (stride > 0 && element.count > (remaining + 1) / stride)
      fail(path, "element '" + element.name + "' announces " + std::to_string(element.count) +
                     " items, more than the file can hold (truncated?)");
    const uint64_t whole =
        stride > 0 ? std::min<uint64_t>(element.count, remaining / stride) : element.count;
    const auto truncated = [&] {
      fail(path, element.name + " " + std::to_string(whole) +
                     ": the file ends inside the data (truncated)");
    };
    if (&element != &vertex) {
      if (whole < element.count) truncated();
      pos += element.count * stride, remaining -= element.count * stride;
      continue;
    }
    const size_t coefficients = size_t(shCoefficientCount(layout.degree));
    cloud.centres.resize(element.count);
    cloud.scales.resize(element.count);
    cloud.rotations.resize(element.count);
    cloud.opacities.resize(element.count);
    cloud.sh.resize(element.count * coefficients);
    // Blocks of whole records, each decoded on every core; the first bad splat of a block (by
    // index, not by which thread saw it first) is reported, as the whole-file reader would.
    constexpr uint64_t kBlockBytes = 32 << 20;
    const uint64_t perBlock = std::max<uint64_t>(1, kBlockBytes / stride);
    std::string block;
    in.clear();
    in.seekg(std::streamoff(pos));
    for (uint64_t first = 0; first < whole; first += perBlock) {
      const uint64_t count = std::min(perBlock, whole - first);
      block.resize(size_t(count * stride));
      in.read(block.data(), std::streamsize(block.size()));
      if (size_t(in.gcount()) != block.size()) fail(path, "error while reading the file");
      std::mutex failedMutex;
      uint64_t failedItem = std::numeric_limits<uint64_t>::max();
      std::optional<InputError> failed;
      parallelFor(int64_t(count), 0, 4096, [&](int64_t begin, int64_t end) {
        std::vector<double> record(element.properties.size());
        for (int64_t r = begin; r < end; ++r) {
          const auto* raw =
              reinterpret_cast<const unsigned char*>(block.data()) + size_t(r) * stride;
          for (size_t i = 0; i < record.size(); ++i) {
            const size_t bytes = sizeOf(element.properties[i].type);
            uint64_t bits = 0;
            for (size_t b = 0; b < bytes; ++b)
              bits |= uint64_t(raw[offsets[i] + b]) << (8 * (little ? b : bytes - 1 - b));
            record[i] = ValueReader::decode(element.properties[i].type, bits);
          }
          const uint64_t item = first + uint64_t(r);
          try {
            decodeSplat(path, vertex, layout, record.data(), item, cloud);
          } catch (const InputError& e) {
            std::lock_guard lock(failedMutex);
            if (item < failedItem) failedItem = item, failed = e;
            return;  // this chunk's later splats cannot come first
          }
        }
      });
      if (failed) throw *failed;
    }
    if (whole < element.count) truncated();
    pos += element.count * stride, remaining -= element.count * stride;
  }
  return cloud;
}

std::string splatPlyBytes(const GaussianCloud& cloud) {
  const size_t coefficients = size_t(shCoefficientCount(cloud.shDegree));
  const size_t rest = 3 * (coefficients - 1);
  std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(cloud.size()) + "\n";
  std::vector<std::string> names = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
  for (size_t k = 0; k < rest; ++k) names.push_back("f_rest_" + std::to_string(k));
  for (const char* name :
       {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
    names.push_back(name);
  for (const std::string& name : names) header += "property float " + name + "\n";
  header += "end_header\n";
  std::string bytes = header;
  bytes.resize(header.size() + cloud.size() * names.size() * sizeof(float));
  char* out = bytes.data() + header.size();
  // Little-endian floats: this machine's own order on every platform Debian builds parallax for
  // (amd64, arm64); memcpy keeps the bytes as they are.
  static_assert(std::endian::native == std::endian::little);
  auto put = [&out](double value) {
    const float f = float(value);
    std::memcpy(out, &f, sizeof f);
    out += sizeof f;
  };
  for (size_t g = 0; g < cloud.size(); ++g) {
    const Vec3f& c = cloud.centres[g];
    put(c.x), put(c.y), put(c.z), put(0), put(0), put(0);
    const auto sh = [&](size_t k, int channel) { return cloud.sh[g * coefficients + k][channel]; };
    for (int channel = 0; channel < 3; ++channel) put(sh(0, channel));
    for (int channel = 0; channel < 3; ++channel)
      for (size_t k = 1; k < coefficients; ++k) put(sh(k, channel));
    const double o = std::clamp(double(cloud.opacities[g]), 1e-7, 1.0 - 1e-7);
    put(std::log(o / (1.0 - o)));
    for (int a = 0; a < 3; ++a) put(std::log(double(cloud.scales[g][a])));
    const Quatf& q = cloud.rotations[g];
    put(q.w), put(q.x), put(q.y), put(q.z);
  }
  return bytes;
}

}  // namespace parallax::meshio
