// The shared requests (jobs/requests.h): every check names the request's field.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "parallax/jobs/design_job.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_job.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/scene_request.h"
#include "parallax/jobs/view_job.h"
#include "parallax/render/display_render.h"

namespace parallax::jobs {
namespace {

TEST(Requests, ChecksNameTheirFields) {
  SamplingRequest sampling;
  sampling.spp = 0;
  EXPECT_EQ(fieldOf([&] { sampling.settings(); }), "spp");
  sampling.spp = 4, sampling.jitter = "sideways";
  EXPECT_EQ(fieldOf([&] { sampling.settings(); }), "jitter");
  sampling.jitter = "auto", sampling.bounces = -1;
  EXPECT_EQ(fieldOf([&] { sampling.settings(); }), "bounces");
  sampling.bounces = 0, sampling.threads = 1 << 20;  // more than any machine's threads
  EXPECT_EQ(fieldOf([&] { sampling.settings(); }), "threads");
  sampling.threads = -1;
  EXPECT_EQ(fieldOf([&] { sampling.settings(); }), "threads");
  sampling.threads = 0, sampling.adaptiveThreshold = std::nan("");
  EXPECT_EQ(fieldOf([&] { sampling.settings(); }), "adaptive_threshold");
  sampling.adaptiveThreshold = 2;
  EXPECT_NO_THROW(sampling.settings());
  FilterRequest filter;
  filter.kind = "blur";
  EXPECT_EQ(fieldOf([&] { filter.filter(); }), "filter");
  filter.kind = "view", filter.widthViews = 50;
  EXPECT_EQ(fieldOf([&] { filter.filter(); }), "filter_width");
  FramingRequest framing;
  framing.fit = "sideways";
  EXPECT_EQ(fieldOf([&] { framing.check(); }), "fit");
  LayersRequest layers;
  layers.method = "nmf", layers.rank = 17;
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "rank");
  layers.rank = 2, layers.method = "optimized-image";
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "rank");
  layers.rank = 1, layers.error = "srgb", layers.method = "nmf";
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "layer_error");
  layers.error = "", layers.trainEyes = 0;
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "train_eyes");
  layers.trainEyes = 2;
  for (const char* bad : {"", "1,", "0.05", "1,x", "11", "1,1,1,1,1,1,1,1,1"}) {
    layers.trainDistances = bad;
    EXPECT_EQ(fieldOf([&] { layers.check(); }), "train_distances") << bad;
  }
  layers.trainDistances = "0.85,1.2";
  EXPECT_NO_THROW(layers.check());
  EXPECT_EQ(parseDistances("0.8,1,1.25", "train_distances"), (std::vector<double>{0.8, 1, 1.25}));
  // 0 iterations is no default (a solver runs at least once); the solver's settings without a
  // solver are refused, not ignored.
  layers.trainEyes = 2, layers.iterations = 0;
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "iterations");
  layers.iterations = 1001;
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "iterations");
  layers.iterations = 1;
  EXPECT_NO_THROW(layers.check());
  layers.method = "slits";
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "iterations");
  layers.iterations.reset(), layers.brightness = 2;
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "brightness");
  layers.brightness = 0, layers.error = "linear";
  EXPECT_EQ(fieldOf([&] { layers.check(); }), "layer_error");
  layers.error = "";
  EXPECT_NO_THROW(layers.check());
  RgbdRequest rgbd;
  rgbd.range = "3:1";
  EXPECT_EQ(fieldOf([&] { rgbd.options(); }), "depth_range");
}

}  // namespace
}  // namespace parallax::jobs
