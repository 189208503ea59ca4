#include "parallax/io/json_writer.h"

#include <gtest/gtest.h>

namespace parallax {
namespace {

TEST(JsonWriter, BuildsNestedObjectsAndArraysByPointer) {
  JsonWriter w;
  w.set("/triangles", int64_t(12));
  w.set("/bounds/min", Vec3f(-1, 0, 0.5f));
  w.set("/objects/0/name", "box \"one\"");
  w.set("/objects/1/name", "floor");
  w.set("/ok", true);
  w.setEmptyArray("/warnings");
  EXPECT_EQ(w.dump(-1), R"({"bounds":{"min":[-1.0,0.0,0.5]},"objects":[{"name":"box \"one\""},)"
                        R"({"name":"floor"}],"ok":true,"triangles":12,"warnings":[]})");
}

}  // namespace
}  // namespace parallax
