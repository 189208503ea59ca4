// The views an interlace maps (jobs/interlace_views.h), on their own: one of the two inputs, a
// quilt cut by its layout into views that are its tiles, views of two sizes named by their place,
// and what the record says of them.
#include "parallax/jobs/interlace_views.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/jobs/jobs_test_support.h"

namespace parallax::jobs {
namespace {

// A 3x2 quilt of 4x2 tiles, tile k a flat grey k / 10.
Image quiltOfGreys() {
  Image quilt(12, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 12; ++x) {
      // Looking Glass quilts: view 0 at the bottom left, rows upward.
      const int k = (x / 4) + 3 * (1 - y / 2);
      quilt.at(x, y) = Vec3f(float(k) / 10.0f);
    }
  return quilt;
}

TEST(InterlaceViews, AQuiltIsCutIntoItsTilesLeftmostFirst) {
  InterlaceRequest r;
  r.quiltLayout = QuiltLayout{3, 2, 0.0};
  const Views given = givenViews(r, {}, quiltOfGreys());
  ASSERT_TRUE(given.quilt);
  ASSERT_EQ(given.images.size(), 6u);
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(given.images[k].width(), 4);
    EXPECT_EQ(given.images[k].height(), 2);
    EXPECT_FLOAT_EQ(given.images[k].at(1, 1).x, float(k) / 10.0f) << k;
  }
  JsonWriter record;
  recordInputs(record, r, given);
  const std::string json = record.dump();
  EXPECT_NE(json.find("\"quilt\": \"quilt\""), std::string::npos) << json;  // in memory
  EXPECT_NE(json.find("\"view_count\": 6"), std::string::npos) << json;
  EXPECT_NE(json.find("\"view_size\": \"4x2\""), std::string::npos) << json;
}

TEST(InterlaceViews, RefusalsNameTheirFieldOrTheView) {
  const std::vector<Image> views(3, Image(4, 2));
  InterlaceRequest r;
  EXPECT_EQ(fieldOf([&] { givenViews(r, {}, {}); }), "views");
  EXPECT_EQ(fieldOf([&] { givenViews(r, views, quiltOfGreys()); }), "quilt");
  EXPECT_EQ(fieldOf([&] { givenViews(r, {}, quiltOfGreys()); }), "quilt_layout");
  r.quiltLayout = QuiltLayout{3, 2, 0.0};
  EXPECT_EQ(fieldOf([&] { givenViews(r, views, {}); }), "quilt_layout");
  EXPECT_EQ(fieldOf([&] { viewResampling("cubic"); }), "view_resampling");
  EXPECT_EQ(viewResampling("nearest"), ViewResampling::Nearest);
  r.quiltLayout.reset();
  std::vector<Image> mixed = views;
  mixed[2] = Image(5, 2);
  try {
    givenViews(r, mixed, {});
    ADD_FAILURE() << "views of two sizes";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "views[2]");
  }
  r.views = {"a.png", "b.png", "c.png"};
  try {
    givenViews(r, mixed, {});
    ADD_FAILURE() << "views of two sizes";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "c.png");  // named by its file when it has one
  }
}

}  // namespace
}  // namespace parallax::jobs
