// The typed JSON reader: every complaint names the file and the JSON pointer of the value.
#include "parallax/io/json_reader.h"

#include <gtest/gtest.h>

#include <functional>

#include "parallax/core/error.h"

namespace parallax {
namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(JsonReader, PointersFollowTheDocument) {
  const JsonDocument doc =
      JsonDocument::parseText(R"({"a": {"b": [1, {"c": [0.5, 2, 3]}]}})", "x.json");
  const JsonReader c = doc.root()["a"]["b"].elements()[1]["c"];
  EXPECT_EQ(c.pointer(), "/a/b/1/c");
  EXPECT_EQ(c.file(), "x.json");
  const Vec3f v = c.vec3();
  EXPECT_EQ(v, Vec3f(0.5f, 2, 3));
}

TEST(JsonReader, ErrorsNameFileAndPointer) {
  const JsonDocument doc = JsonDocument::parseText(R"({"color": [1, 2], "n": "x"})", "s.json");
  const JsonReader root = doc.root();
  EXPECT_NE(errorOf([&] { root["color"].vec3(); }).find("s.json: /color:"), std::string::npos);
  EXPECT_NE(errorOf([&] { root["n"].number(); }).find("s.json: /n:"), std::string::npos);
  EXPECT_NE(errorOf([&] { root["missing"]; }).find("missing"), std::string::npos);
}

TEST(JsonReader, UnknownKeysGetAHint) {
  const JsonDocument doc = JsonDocument::parseText(R"({"colr": 1})", "s.json");
  const std::string e = errorOf([&] { doc.root().expectObject({"color", "radius"}); });
  EXPECT_NE(e.find("/colr"), std::string::npos) << e;
  EXPECT_NE(e.find("color"), std::string::npos) << e;
  EXPECT_EQ(closestMatch("raduis", {"color", "radius"}), "radius");
  EXPECT_EQ(closestMatch("zzzzzz", {"color", "radius"}), "");
}

TEST(JsonReader, MalformedTextAndDuplicateKeysAreErrors) {
  EXPECT_NE(errorOf([] { JsonDocument::parseText(R"({"a": [1, 2)", "t.json"); }).find("t.json"),
            std::string::npos);
  EXPECT_NE(
      errorOf([] { JsonDocument::parseText(R"({"a": 1, "a": 2})", "d.json"); }).find("d.json"),
      std::string::npos);
  // Comments are allowed.
  const JsonDocument doc = JsonDocument::parseText("{ // note\n \"a\": /* x */ 1 }", "c.json");
  EXPECT_EQ(doc.root()["a"].number(), 1.0);
}

}  // namespace
}  // namespace parallax
