// The PLY format both PLY readers share (importer/ply_format.h): the header as declared, the
// values in each encoding decoded to what was written, and a count the file cannot hold refused.
#include "parallax/importer/ply_format.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/importer/mesh_test_support.h"

namespace parallax::meshio {
namespace {

const std::string kHeader =
    "ply\nformat binary_big_endian 1.0\ncomment made by hand\nelement vertex 2\n"
    "property float x\nproperty uchar red\nelement face 1\n"
    "property list uchar int vertex_indices\nend_header\n";

TEST(PlyFormat, TheHeaderIsWhatItDeclares) {
  std::vector<std::string> warnings;
  const Header header = parsePlyHeader("h.ply", kHeader, warnings);
  EXPECT_EQ(header.format, Format::BinaryBigEndian);
  ASSERT_EQ(header.elements.size(), 2u);
  EXPECT_EQ(header.elements[0].name, "vertex");
  EXPECT_EQ(header.elements[0].count, 2u);
  ASSERT_EQ(header.elements[0].properties.size(), 2u);
  EXPECT_EQ(header.elements[0].properties[1].type, Type::UInt8);
  const Property& list = header.elements[1].properties[0];
  EXPECT_TRUE(list.isList);
  EXPECT_EQ(list.countType, Type::UInt8);
  EXPECT_EQ(list.type, Type::Int32);
  EXPECT_EQ(header.dataOffset, kHeader.size());
  EXPECT_TRUE(warnings.empty());
  EXPECT_THROW(parsePlyHeader("h.ply", "ply\nformat ascii 1.0\nelement vertex 2\n", warnings),
               InputError);  // no end_header
  EXPECT_THROW(
      parsePlyHeader("h.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", warnings),
      InputError);  // a property before any element
}

TEST(PlyFormat, ValuesDecodeInEveryEncoding) {
  meshtest::Bytes big;
  big.bigEndian = true;
  big.f32(1.5f).put(uint8_t(200)).f32(-2.25f).put(uint8_t(7));
  const std::string bytes = kHeader + big.data;
  std::vector<std::string> warnings;
  const Header header = parsePlyHeader("b.ply", bytes, warnings);
  ValueReader values("b.ply", bytes, header);
  EXPECT_EQ(values.read(Type::Float32, "v"), 1.5);
  EXPECT_EQ(values.read(Type::UInt8, "v"), 200);
  EXPECT_EQ(values.read(Type::Float32, "v"), -2.25);
  EXPECT_EQ(values.read(Type::UInt8, "v"), 7);
  EXPECT_THROW(values.read(Type::UInt8, "face 0"), InputError);  // the file ends here

  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
      "property int n\nend_header\n-0.125 -42\n";
  const Header text = parsePlyHeader("a.ply", ascii, warnings);
  ValueReader words("a.ply", ascii, text);
  EXPECT_EQ(words.read(Type::Float32, "v"), -0.125);
  EXPECT_EQ(words.read(Type::Int32, "v"), -42);
}

TEST(PlyFormat, ACountTheFileCannotHoldIsRefusedNamingTheElement) {
  meshtest::Bytes one;
  one.bigEndian = true;
  one.f32(1.0f).put(uint8_t(1));  // one vertex of the two announced
  const std::string bytes = kHeader + one.data;
  std::vector<std::string> warnings;
  const Header header = parsePlyHeader("c.ply", bytes, warnings);
  const ValueReader values("c.ply", bytes, header);
  try {
    checkCountFits("c.ply", header.elements[0], values);
    ADD_FAILURE() << "two vertices fit in five bytes";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("element 'vertex' announces 2 items"), std::string::npos);
  }
  Element fits = header.elements[0];
  fits.count = 1;
  EXPECT_NO_THROW(checkCountFits("c.ply", fits, values));
}

}  // namespace
}  // namespace parallax::meshio
