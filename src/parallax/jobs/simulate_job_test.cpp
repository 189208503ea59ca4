#include "parallax/jobs/simulate_job.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "parallax/core/error.h"
#include "parallax/io/display_file.h"
#include "parallax/io/json_reader.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/limits.h"

namespace parallax::jobs {
namespace {

BuiltDisplay barrier() {
  return makeDisplay(loadDisplayDescription(""));
}
BuiltDisplay lenticular() {
  return makeDisplay(loadDisplayDescription("lkg:go"));
}

// The field a RequestError names, or "" when `run` throws none.
std::string refusedField(const std::function<void()>& run) {
  try {
    run();
  } catch (const RequestError& e) {
    return e.field();
  }
  return "";
}

// The field simulationOptions refuses in the request that `set` makes, or "".
std::string refusedOption(const DisplayModel& display,
                          const std::function<void(SimulatorRequest&)>& set) {
  SimulatorRequest r;
  set(r);
  return refusedField([&] { simulationOptions(r, display); });
}

TEST(SimulatorRequest, ChecksNameTheirFields) {
  const BuiltDisplay display = barrier();
  const auto field = [&display](const std::function<void(SimulatorRequest&)>& set) {
    return refusedOption(*display, set);
  };
  EXPECT_EQ(field([](SimulatorRequest&) {}), "");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.spp = 2; }), "spp");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.spp = -4; }), "spp");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.pupil = 101; }), "pupil");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.pupilSamples = 0; }), "pupil_samples");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.diffuser = -1; }), "diffuser");
  // A blur wider than the display is no diffuser.
  EXPECT_EQ(field([](SimulatorRequest& r) { r.diffuser = 1e5; }), "diffuser");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.size = {{0, 10}}; }), "size");
}

TEST(SimulatorRequest, BecomesTheSimulatorsOptions) {
  SimulatorRequest r;
  r.size = {{64, 36}};
  r.spp = 9, r.pupil = 3, r.pupilSamples = 4, r.diffuser = 0.5, r.colorFilters = true;
  r.raw = true, r.threads = 2;
  const SimulationOptions sim = simulationOptions(r, *barrier());
  EXPECT_EQ(sim.width, 64);
  EXPECT_EQ(sim.height, 36);
  EXPECT_EQ(sim.samplesPerPixel, 9);
  EXPECT_EQ(sim.pupilDiameterMm, 3);
  EXPECT_EQ(sim.pupilSamples, 4);
  EXPECT_EQ(sim.diffuserSigmaMm, 0.5);
  EXPECT_TRUE(sim.colourFilters);
  EXPECT_FALSE(sim.normalise);
  EXPECT_EQ(sim.threads, 2);
}

// The two-layer simulator's options are refused for a lenticular panel, each by its field.
TEST(SimulatorRequest, LenticularRefusesTheTwoLayerOptions) {
  const BuiltDisplay display = lenticular();
  const auto field = [&display](const std::function<void(SimulatorRequest&)>& set) {
    return refusedOption(*display, set);
  };
  EXPECT_EQ(field([](SimulatorRequest& r) { r.rawPixels = true; }), "");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.size = {{64, 36}}; }), "size");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.spp = 4; }), "spp");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.pupil = 3; }), "pupil");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.diffuser = 0.1; }), "diffuser");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.colorFilters = true; }), "color_filters");
  EXPECT_EQ(field([](SimulatorRequest& r) { r.raw = true; }), "raw");
  try {
    SimulatorRequest r;
    r.pupil = 3;
    simulationOptions(r, *display);
    FAIL() << "pupil on a lenticular panel was not refused";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.message().rfind("applies to the two-layer (barrier) simulator", 0), 0u);
  }
  EXPECT_EQ(refusedField([&] { checkMaskLayer(*display, true); }), "mask");
  EXPECT_EQ(refusedField([&] { checkMaskLayer(*display, false); }), "");
  EXPECT_EQ(refusedField([&] { checkMaskLayer(*barrier(), true); }), "");
  // Before any work: the refusal comes from the request, not the simulator.
  SimulatorRequest r;
  r.pupil = 3;
  EXPECT_EQ(refusedField([&] { simulatedPictures(*display, {}, r, {{0, 0, 600}}); }), "pupil");
}

// The sweep's eyes are the display's analytic positions across its view zone, scaled to the
// sweep's distance.
TEST(Sweep, EyesAreTheZonesPositions) {
  for (const char* source : {"", "lkg:go"}) {
    const BuiltDisplay display = makeDisplay(loadDisplayDescription(source));
    const Vec3d centre = display->window().eyeMm;
    const std::vector<Vec3d> eyes = sweepEyes(*display, {5, 1.0, 0.0});
    ASSERT_EQ(eyes.size(), 5u);
    for (int i = 0; i < 5; ++i) {
      const Vec3d e = display->eyeAcrossZone(i / 4.0);
      EXPECT_NEAR(eyes[i].x, e.x, 1e-9) << i;
      EXPECT_EQ(eyes[i].y, centre.y);
      EXPECT_EQ(eyes[i].z, centre.z);
    }
    EXPECT_NEAR(eyes[4].x - eyes[0].x, display->viewZoneWidthMm(), 1e-6);
    // Twice as far, twice as wide; half the range, the zone's middle half; one eye: the centre.
    const std::vector<Vec3d> far = sweepEyes(*display, {5, 1.0, 2 * centre.z});
    EXPECT_NEAR(far[4].x - far[0].x, 2 * display->viewZoneWidthMm(), 1e-6);
    EXPECT_EQ(far[2].z, 2 * centre.z);
    const std::vector<Vec3d> half = sweepEyes(*display, {3, 0.5, 0.0});
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(half[i].x, display->eyeAcrossZone(0.25 + 0.25 * i).x, 1e-9) << i;
    EXPECT_NEAR(sweepEyes(*display, {1, 1.0, 0.0})[0].x, centre.x, 1e-9);
  }
}

TEST(Sweep, ChecksNameTheirFields) {
  const BuiltDisplay display = barrier();
  const auto field = [&display](const SweepRequest& sweep) {
    return refusedField([&] { sweepEyes(*display, sweep); });
  };
  EXPECT_EQ(field({0, 1.0, 0.0}), "sweep");
  EXPECT_EQ(field({3, 0.0, 0.0}), "sweep_range");
  EXPECT_EQ(field({3, 11.0, 0.0}), "sweep_range");
  EXPECT_EQ(field({3, 1.0, -5.0}), "sweep_distance");
  EXPECT_EQ(field({3, 1.0, 1e9}), "sweep_distance");
}

TEST(SimulatedEyes, NonFiniteAndFarEyesAreRefused) {
  const BuiltDisplay display = barrier();
  for (const Vec3d& e : {Vec3d{std::nan(""), 0, 600}, Vec3d{1e300, 0, 600},
                         Vec3d{0, 0, std::numeric_limits<double>::infinity()}, Vec3d{0, 0, 2e6}})
    EXPECT_EQ(refusedField([&] { simulatedEyes(*display, {e}); }), "eye");
  EXPECT_EQ(refusedField([&] { simulatedEyes(*display, {Vec3d{1e6, -1e6, 1e6}}); }), "");
}

TEST(SimulatedEyes, GivenThenSweptElseTheCentre) {
  const BuiltDisplay display = barrier();
  const std::vector<Vec3d> centre = simulatedEyes(*display, {});
  ASSERT_EQ(centre.size(), 1u);
  EXPECT_EQ(centre[0].x, display->window().eyeMm.x);
  EXPECT_EQ(centre[0].z, display->window().eyeMm.z);
  const std::vector<Vec3d> eyes = simulatedEyes(*display, {{10, 0, 600}}, {3, 1.0, 0.0});
  ASSERT_EQ(eyes.size(), 4u);
  EXPECT_EQ(eyes[0].x, 10);
  EXPECT_EQ(refusedField([&] { simulatedEyes(*display, {{0, 0, -1}}); }), "eye");
}

// The memory estimate refuses an absurd size before anything is allocated, naming {size}.
TEST(SimulationWork, MemoryEstimateRefusesAnAbsurdSize) {
  const BuiltDisplay display = barrier();
  const Limits saved = limits();
  limits().maxMemoryGiB = 1;
  SimulatorRequest r;
  r.size = {{65536, 65536}};
  try {
    checkSimulationWork(*display, {}, r, 1);
    ADD_FAILURE() << "65536 x 65536 within 1 GiB";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "{size} 65536x65536");
    EXPECT_NE(std::string(e.what()).find("{max_memory}"), std::string::npos) << e.what();
  }
  // A sweep names its step count; a small size passes.
  try {
    checkSimulationWork(*display, {}, SimulatorRequest{}, 100000, 100000);
    ADD_FAILURE() << "100000 sweep steps within 1 GiB";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "{sweep} 100000");
  }
  r.size = {{64, 36}};
  EXPECT_NO_THROW(checkSimulationWork(*display, {}, r, 1));
  limits() = saved;
}

TEST(SimulationWork, TimeEstimateNamesTheField) {
  const BuiltDisplay display = barrier();
  const Limits saved = limits();
  limits().maxSeconds = 1e-9;
  EXPECT_EQ(refusedField([&] { checkSimulationWork(*display, {}, {}, 1); }), "spp");
  EXPECT_EQ(refusedField([&] { checkSimulationWork(*display, {}, {}, 3, 3); }), "sweep");
  limits() = saved;
  limits().maxSeconds = 1;
  SimulatorRequest r;
  r.size = {{64, 36}};
  EXPECT_EQ(refusedField([&] { checkSimulationWork(*display, {}, r, 1, 0, 1 << 30); }),
            "reference_spp");
  limits() = saved;
}

// Layers no panel shows are refused naming the layer and the first bad pixel; an image layer
// above 1 (a linear layer's highlights) and a mask of exactly 0 and 1 are taken.
TEST(SimulationWork, LayerValuesAreChecked) {
  const auto layers = [](float image, float mask) {
    LayerImages l{Image(4, 3, Vec3f(0.5f)), Image(4, 3, Vec3f(1.0f))};
    l.image.at(2, 1).y = image;
    l.mask.at(3, 2).z = mask;
    return l;
  };
  const auto message = [&](float image, float mask) -> std::string {
    try {
      checkLayerValues(layers(image, mask));
    } catch (const RequestError& e) {
      return e.field() + ": " + e.what();
    }
    return "";
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(refusedField([&] { checkLayerValues(layers(nan, 1)); }), "image");
  EXPECT_NE(message(nan, 1).find("pixel (2, 1) channel 1 is NaN"), std::string::npos)
      << message(nan, 1);
  EXPECT_NE(message(inf, 1).find("is infinite"), std::string::npos);
  EXPECT_NE(message(-0.25f, 1).find("is -0.25"), std::string::npos);
  EXPECT_EQ(refusedField([&] { checkLayerValues(layers(0.5f, -1)); }), "mask");
  EXPECT_NE(message(0.5f, 1.5f).find("pixel (3, 2) channel 2 is 1.5: a transmittance"),
            std::string::npos)
      << message(0.5f, 1.5f);
  EXPECT_EQ(refusedField([&] { checkLayerValues(layers(0.5f, nan)); }), "mask");
  EXPECT_EQ(message(7.0f, 0.0f), "");
  EXPECT_EQ(message(0.0f, 1.0f), "");
  // checkSimulationWork, which every simulate path runs, checks them.
  EXPECT_EQ(refusedField([&] { checkSimulationWork(*barrier(), layers(nan, 1), {}, 1); }), "image");
}

TEST(Quality, RefusesReferenceSppBelowOne) {
  EXPECT_EQ(refusedField([] { checkReferenceSpp(0); }), "reference_spp");
  EXPECT_EQ(refusedField([] { checkReferenceSpp(1); }), "");
}

TEST(Quality, RecordsEyesAndTheirMean) {
  JsonWriter json;
  EyeFigures a, b;
  a.psnr = 30, b.psnr = 40, a.ownView = 2, b.ownView = 3;
  recordEyeFigures(json, {{0, 0, 600}, {10, 0, 600}}, {a, b});
  const JsonDocument record = JsonDocument::parseText(json.dump(), "test");
  EXPECT_EQ(record.root()["eyes"].elements().size(), 2u);
  EXPECT_EQ(record.root()["eyes"].elements()[1]["own_view"].number(), 3);
  EXPECT_EQ(record.root()["mean"]["psnr"].number(), 35);
  JsonWriter eyesOnly;
  recordEyeFigures(eyesOnly, {{0, 0, 600}}, {});
  EXPECT_EQ(eyesOnly.dump().find("mean"), std::string::npos);
}

}  // namespace
}  // namespace parallax::jobs
