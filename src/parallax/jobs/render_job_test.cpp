// The render runner (jobs/render_job.h) against the library's own calls (a second code path),
// and its refusals before any work.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/io/display_file.h"
#include "parallax/jobs/design_job.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_job.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/view_job.h"
#include "parallax/render/display_render.h"
#include "parallax/render/display_test_support.h"

namespace parallax::jobs {
namespace {

TEST(RenderRunner, InMemoryLayersAreTheLibrarysLayers) {
  const Scene scene = defaultScene();
  RenderRequest request;
  request.display.loaded = smallBarrier();
  request.sampling.spp = 4;
  RecordingReporter reporter;
  const RenderResult result = renderInMemory(request, scene, reporter);
  ASSERT_EQ(result.frames.size(), 1u);

  // The same layers through the library alone: framed, accelerated and rendered by hand.
  Scene framed = defaultScene();
  const Framing framing = frameForDisplay(framed, designDisplay(smallDisplaySpec(90, 30)));
  framed.display = framing.placement;
  const Accelerator accelerator(framed);
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  const DisplayLayers expected =
      renderDisplay(framed, accelerator, *makeBarrierDisplay(framing.design), settings);
  EXPECT_EQ(result.frames[0].image.pixels(), expected.image.pixels());
  EXPECT_EQ(result.frames[0].mask.pixels(), expected.mask.pixels());
  EXPECT_NE(result.record.find("\"method\": \"barrier-camera\""), std::string::npos);
  EXPECT_NE(result.record.find("\"spp\": 4"), std::string::npos);
}

TEST(RenderRunner, RefusesBeforeAnyWork) {
  const Scene scene = defaultScene();
  RenderRequest request;
  request.display.loaded = smallBarrier();
  request.quilt.width = request.quilt.height = 64;  // a tile size without a quilt
  EXPECT_EQ(fieldOf([&] { renderInMemory(request, scene, silentReporter()); }), "size");
  request.quilt = {};
  request.sequence.frames = "1:2";
  EXPECT_EQ(fieldOf([&] { renderInMemory(request, scene, silentReporter()); }), "sequence");
  request.sequence = {};
  request.display.loaded = portrait();
  request.directMapping = true;
  EXPECT_EQ(fieldOf([&] { renderInMemory(request, scene, silentReporter()); }), "direct_mapping");
  request.directMapping = false;
  request.layers.method = "nmf";
  EXPECT_EQ(fieldOf([&] { renderInMemory(request, scene, silentReporter()); }), "layers");
}

// `{filter} none` casts each pixel's central ray, so more samples would trace it again: the
// runner says so, naming both fields, on either display kind, and renders one sample a pixel.
TEST(RenderRunner, FilterNoneSaysWhatItDoesWithSpp) {
  const Scene scene = defaultScene();
  DisplayDescription smallPanel = portrait();
  smallPanel.lenticular.screenW /= 8, smallPanel.lenticular.screenH /= 8;
  for (const DisplayDescription& display : {smallBarrier(), smallPanel}) {
    RenderRequest request;
    request.display.loaded = display;
    request.filter.kind = "none";
    request.sampling.spp = 4;
    RecordingReporter reporter;
    const RenderResult result = renderInMemory(request, scene, reporter);
    const auto filterNotes = [](const RecordingReporter& said) {
      std::vector<std::string> notes;
      for (const std::string& n : said.notes)
        if (n.find("{filter} none") != std::string::npos) notes.push_back(n);
      return notes;
    };
    ASSERT_EQ(filterNotes(reporter).size(), 1u) << display.source();
    const std::string note = filterNotes(reporter)[0];
    EXPECT_NE(note.find("{filter} none casts each film pixel's central ray"), std::string::npos)
        << note;
    EXPECT_NE(note.find("{spp} 4 renders as 1 sample a pixel"), std::string::npos) << note;
    EXPECT_NE(result.record.find("\"spp\": 1"), std::string::npos);
    // Said only when it changes something: one sample, or a filter that spreads them.
    request.sampling.spp = 1;
    RecordingReporter quiet;
    renderInMemory(request, scene, quiet);
    EXPECT_TRUE(filterNotes(quiet).empty());
    request.sampling.spp = 4;
    request.filter.kind = "view";
    renderInMemory(request, scene, quiet);
    EXPECT_TRUE(filterNotes(quiet).empty());
  }
}

TEST(RenderRunner, AQuiltInMemoryTakesTheDisplaysOwnLayout) {
  const Scene scene = defaultScene();
  RenderRequest request;
  request.display.loaded = smallBarrier();
  request.sampling.spp = 1;
  request.quilt.wanted = true;
  request.quilt.width = 30, request.quilt.height = 10;
  const RenderResult result = renderInMemory(request, scene, silentReporter());
  // auto: one row of the barrier's 9 views.
  EXPECT_EQ(result.quilt.width(), 9 * 30);
  EXPECT_EQ(result.quilt.height(), 10);
  EXPECT_NE(result.record.find("quilt_qs9x1a3.png"), std::string::npos) << result.record;
}

}  // namespace
}  // namespace parallax::jobs
