#include "parallax/importer/splat_ply.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
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
      Vec3f* sh = &cloud.sh[item * coefficients];
      for (int c = 0; c < 3; ++c) {
        sh[0][c] = float(field(layout.dc[c]));
        // f_rest is channel-major: channel c's coefficients 1.. are f_rest_{c (K - 1) + k - 1}.
        for (size_t k = 1; k < coefficients; ++k)
          sh[k][c] = float(field(layout.rest[size_t(c) * (coefficients - 1) + k - 1]));
      }
    }
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
    const Vec3f* sh = &cloud.sh[g * coefficients];
    for (int channel = 0; channel < 3; ++channel) put(sh[0][channel]);
    for (int channel = 0; channel < 3; ++channel)
      for (size_t k = 1; k < coefficients; ++k) put(sh[k][channel]);
    const double o = std::clamp(double(cloud.opacities[g]), 1e-7, 1.0 - 1e-7);
    put(std::log(o / (1.0 - o)));
    for (int a = 0; a < 3; ++a) put(std::log(double(cloud.scales[g][a])));
    const Quatf& q = cloud.rotations[g];
    put(q.w), put(q.x), put(q.y), put(q.z);
  }
  return bytes;
}

}  // namespace parallax::meshio
