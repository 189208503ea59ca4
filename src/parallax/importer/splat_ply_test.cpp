// Gaussian splats in PLY files (importer/splat_ply.h): 3DGS's layout in the reference order and in
// splat-transform's (no normals, the fields in another order), in each encoding, its encodings
// undone against values worked by hand; every refusal names the file, the splat and the field.
#include "parallax/importer/splat_ply.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "parallax/importer/mesh_readers.h"
#include "parallax/importer/mesh_test_support.h"

namespace parallax::meshio {
namespace {

using meshtest::Bytes;
using meshtest::TempDir;
using meshtest::writeFile;

// Splat g's value of property `name` (the file's encoding), distinct for every splat and field.
double encoded(const std::string& name, int g) {
  if (name == "x" || name == "y" || name == "z") return 0.5 * g + (name[0] - 'x');
  if (name.rfind("scale_", 0) == 0) return -2.0 - 0.25 * (name.back() - '0') + 0.1 * g;
  if (name == "opacity") return 0.3 * g - 1.0;
  if (name == "rot_0") return 2.0;  // unnormalised, as files keep it
  if (name.rfind("rot_", 0) == 0) return 0.1 * (name.back() - '0') + 0.01 * g;
  if (name.rfind("f_dc_", 0) == 0) return 0.2 * (name.back() - '0') - 0.1 * g;
  if (name.rfind("f_rest_", 0) == 0) return 0.001 * std::stoi(name.substr(7)) + 0.1 * g;
  return 7.0;  // normals and anything else: read past
}

std::vector<std::string> referenceOrder(int restCount) {
  std::vector<std::string> names = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
  for (int k = 0; k < restCount; ++k) names.push_back("f_rest_" + std::to_string(k));
  for (const char* n :
       {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
    names.push_back(n);
  return names;
}

// splat-transform's order: no normals, the rotation and scale before the colour.
std::vector<std::string> splatTransformOrder(int restCount) {
  std::vector<std::string> names = {"x",       "y",      "z",       "rot_0",   "rot_1",
                                    "rot_2",   "rot_3",  "scale_0", "scale_1", "scale_2",
                                    "opacity", "f_dc_0", "f_dc_1",  "f_dc_2"};
  for (int k = 0; k < restCount; ++k) names.push_back("f_rest_" + std::to_string(k));
  return names;
}

std::string splatPly(const std::vector<std::string>& names, int count, const std::string& format,
                     int announced = -1) {
  std::string text = "ply\nformat " + format + " 1.0\nelement vertex " +
                     std::to_string(announced < 0 ? count : announced) + "\n";
  for (const std::string& n : names) text += "property float " + n + "\n";
  text += "end_header\n";
  Bytes data;
  data.bigEndian = format == "binary_big_endian";
  for (int g = 0; g < count; ++g)
    for (const std::string& n : names) {
      if (format == "ascii")
        text += std::to_string(encoded(n, g)) + (&n == &names.back() ? "\n" : " ");
      else
        data.f32(float(encoded(n, g)));
    }
  return text + data.data;
}

GaussianCloud read(const TempDir& dir, const std::string& bytes) {
  const std::string path = dir.file("splats.ply");
  writeFile(path, bytes);
  const FileContents contents = readPly(path);
  EXPECT_TRUE(contents.splats.has_value());
  EXPECT_TRUE(contents.parts.empty());
  return contents.splats.value_or(GaussianCloud{});
}

std::string refusal(const TempDir& dir, const std::string& bytes) {
  const std::string path = dir.file("bad.ply");
  writeFile(path, bytes);
  try {
    readPly(path);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    return e.what();
  }
  return "(read)";
}

TEST(SplatPly, ReadsThe3dgsLayoutAndUndoesItsEncodings) {
  const TempDir dir;
  for (const int degree : {0, 1, 2, 3}) {
    const int rest = 3 * (shCoefficientCount(degree) - 1);
    const GaussianCloud cloud =
        read(dir, splatPly(referenceOrder(rest), 3, "binary_little_endian"));
    ASSERT_EQ(cloud.size(), 3u) << degree;
    EXPECT_EQ(cloud.shDegree, degree);
    const size_t count = size_t(shCoefficientCount(degree));
    ASSERT_EQ(cloud.sh.size(), 3 * count);
    for (int g = 0; g < 3; ++g) {
      EXPECT_FLOAT_EQ(cloud.centres[g].x, float(encoded("x", g)));
      EXPECT_FLOAT_EQ(cloud.centres[g].z, float(encoded("z", g)));
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(cloud.scales[g][c],
                    std::exp(double(float(encoded("scale_" + std::to_string(c), g)))), 1e-6);
      EXPECT_NEAR(cloud.opacities[g], 1 / (1 + std::exp(-double(float(encoded("opacity", g))))),
                  1e-6);
      EXPECT_FLOAT_EQ(cloud.rotations[g].w, 2.0f);  // kept as written; normalised where used
      EXPECT_FLOAT_EQ(cloud.rotations[g].z, float(encoded("rot_3", g)));
      // Coefficient-major: coefficient k of channel c is f_dc_c (k = 0) or f_rest_{c (K-1) + k-1}.
      for (size_t k = 0; k < count; ++k)
        for (int c = 0; c < 3; ++c) {
          const std::string name =
              k == 0 ? "f_dc_" + std::to_string(c)
                     : "f_rest_" + std::to_string(size_t(c) * (count - 1) + k - 1);
          // Kept in half floats (gaussians.h): the file's value rounded to one.
          EXPECT_EQ(cloud.sh[size_t(g) * count + k][c], fromHalf(toHalf(float(encoded(name, g)))))
              << "degree " << degree << " splat " << g << " k " << k << " channel " << c;
        }
    }
  }
}

TEST(SplatPly, EveryEncodingAndOrderReadsTheSameSplats) {
  const TempDir dir;
  const GaussianCloud reference =
      read(dir, splatPly(referenceOrder(45), 4, "binary_little_endian"));
  for (const auto& [names, format] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {referenceOrder(45), "binary_big_endian"},
           {splatTransformOrder(45), "binary_little_endian"},
           {referenceOrder(45), "ascii"}}) {
    const GaussianCloud cloud = read(dir, splatPly(names, 4, format));
    ASSERT_EQ(cloud.size(), reference.size()) << format;
    const float tolerance = format == "ascii" ? 1e-5f : 0.0f;  // std::to_string's 6 decimals
    for (size_t g = 0; g < cloud.size(); ++g) {
      EXPECT_NEAR(cloud.opacities[g], reference.opacities[g], tolerance) << format;
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(cloud.scales[g][c], reference.scales[g][c], tolerance) << format;
    }
    for (size_t i = 0; i < cloud.sh.size(); ++i)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(cloud.sh[i][c], reference.sh[i][c], tolerance) << format << " " << i;
  }
}

TEST(SplatPly, RefusesNamingTheSplatAndTheField) {
  const TempDir dir;
  std::vector<std::string> lacking = referenceOrder(0);
  lacking.pop_back();  // rot_3
  EXPECT_NE(refusal(dir, splatPly(lacking, 2, "binary_little_endian")).find("rot_3"),
            std::string::npos);
  EXPECT_NE(refusal(dir, splatPly(referenceOrder(10), 2, "binary_little_endian"))
                .find("f_rest_0..9: 10 coefficients are no degree's"),
            std::string::npos);
  // Counts that lie: more splats announced than the file holds.
  EXPECT_NE(refusal(dir, splatPly(referenceOrder(9), 2, "binary_little_endian", 1000))
                .find("announces 1000 items, more than the file can hold"),
            std::string::npos);
  // Truncated inside the last splat.
  std::string cut = splatPly(referenceOrder(9), 3, "binary_little_endian");
  cut.resize(cut.size() - 6);
  EXPECT_NE(refusal(dir, cut).find("truncated"), std::string::npos);
  // A value that is not a number, an absurd scale, no rotation.
  const auto withValue = [&](const std::string& field, float value) {
    std::string bytes = splatPly(referenceOrder(0), 2, "binary_little_endian");
    const std::vector<std::string> names = referenceOrder(0);
    const size_t at = bytes.size() - 4 * names.size() +
                      4 * size_t(std::find(names.begin(), names.end(), field) - names.begin());
    std::memcpy(&bytes[at], &value, 4);  // splat 1's field (the test host is little-endian)
    return refusal(dir, bytes);
  };
  EXPECT_NE(withValue("opacity", std::nanf("")).find("splat 1: opacity is not a finite number"),
            std::string::npos);
  EXPECT_NE(withValue("scale_2", 40.0f).find("splat 1: scale_2 is 40"), std::string::npos);
  EXPECT_NE(withValue("y", INFINITY).find("splat 1: y is not a finite number"), std::string::npos);
  std::string noRotation = splatPly(referenceOrder(0), 1, "ascii");
  const size_t rot = noRotation.rfind("2.000000");  // rot_0 of the one splat
  noRotation.replace(rot, 8, "0");
  // rot_1..3 of splat 0 are 0.1, 0.2, 0.3: set them to 0 too.
  for (const char* v : {"0.100000", "0.200000", "0.300000"})
    noRotation.replace(noRotation.rfind(v), 8, "0");
  EXPECT_NE(refusal(dir, noRotation).find("splat 0: rot_0..3 is the zero quaternion"),
            std::string::npos);
}

// A bare splat file given as a scene is read whole, then refused in one line that says what it
// holds: the renderer does not take splats yet.
TEST(SplatPly, ASplatFileLoadsAsSplatsNotAsAMesh) {
  const TempDir dir;
  const std::string path = dir.file("capture.ply");
  writeFile(path, splatPly(referenceOrder(45), 5, "binary_little_endian"));
  const Scene scene = meshtest::load(path);
  EXPECT_TRUE(scene.meshes.empty());
  ASSERT_EQ(scene.splats.size(), 1u);
  EXPECT_EQ(scene.splats[0].cloud.size(), 5u);
  EXPECT_EQ(scene.splats[0].cloud.shDegree, 3);
  // COLMAP's frame, turned Y-up: 180 degrees about X.
  EXPECT_EQ(scene.splats[0].worldFromFile.point({1, 2, 3}), Vec3f(1, -2, -3));
  ASSERT_EQ(scene.imports.size(), 1u);
  EXPECT_EQ(scene.imports[0].splats, 5u);
  EXPECT_EQ(scene.imports[0].up, "-y");
}

TEST(SplatPly, WhatTheWriterWritesTheReaderReads) {
  GaussianCloud cloud;
  cloud.shDegree = 2;
  for (int g = 0; g < 3; ++g) {
    cloud.centres.push_back({float(g), 0.5f * float(g), -1.0f});
    cloud.scales.push_back({0.1f * float(g + 1), 0.02f, 0.3f});
    cloud.rotations.push_back({0.9f, 0.1f * float(g), -0.2f, 0.3f});
    cloud.opacities.push_back(0.2f + 0.3f * float(g));
    for (int k = 0; k < 9; ++k) cloud.sh.push_back({0.01f * float(k), -0.02f * float(k), float(g)});
  }
  const std::string bytes = splatPlyBytes(cloud);
  std::vector<std::string> warnings;
  const GaussianCloud back =
      readSplats("written.ply", bytes, parsePlyHeader("written.ply", bytes, warnings));
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back.shDegree, 2);
  for (size_t g = 0; g < 3; ++g) {
    EXPECT_EQ(back.centres[g], cloud.centres[g]);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(back.scales[g][a], cloud.scales[g][a], 1e-6f);
    EXPECT_EQ(back.rotations[g].x, cloud.rotations[g].x);
    EXPECT_NEAR(back.opacities[g], cloud.opacities[g], 1e-6f);
    for (size_t k = 0; k < 9; ++k) EXPECT_EQ(back.sh[g * 9 + k], cloud.sh[g * 9 + k]);
  }
}

TEST(SplatPly, AnElementAfterTheSplatsWithMorePropertiesIsReadPast) {
  // The splats, then another element called "vertex" with more properties than theirs: a
  // fuzzer's find, where the reader wrote the second element's values past a record of the
  // splats' size. The splats are the first vertex element; the rest is read past.
  const TempDir dir;
  const std::string path = dir.file("two.ply");
  std::string text =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nproperty float f_dc_0\nproperty float f_dc_1\nproperty float f_dc_2\n"
      "property float opacity\nproperty float scale_0\nproperty float scale_1\n"
      "property float scale_2\nproperty float rot_0\nproperty float rot_1\n"
      "property float rot_2\nproperty float rot_3\nelement vertex 1\n";
  for (int p = 0; p < 40; ++p) text += "property float p" + std::to_string(p) + "\n";
  text += "end_header\n0 0 0 0 0 0 0 0 0 0 1 0 0 0\n";
  for (int p = 0; p < 40; ++p) text += "1 ";
  text += "\n";
  writeFile(path, text);
  const Scene scene = meshtest::load(path);
  ASSERT_EQ(scene.splats.size(), 1u);
  EXPECT_EQ(scene.splats[0].cloud.size(), 1u);
}

}  // namespace
}  // namespace parallax::meshio
