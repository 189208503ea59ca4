#include "parallax/io/display_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "parallax/core/error.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

std::string writeTemp(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "parallax_display_file_test";
  fs::create_directories(dir);
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

DisplayDesign designFile(const std::string& path) {
  const BarrierDisplayFile file = loadDisplayFile(path);
  return designDisplay(file.spec, file.camera);
}

TEST(DisplayFile, EveryExampleLoadsAndDesigns) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(PARALLAX_SOURCE_DIR) / "displays")) {
    if (!entry.is_regular_file() || entry.path().extension() != ".json") continue;
    const DisplayDesign d = designFile(entry.path().string());
    EXPECT_GT(d.views, 2.0) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 5);
}

TEST(DisplayFile, DefaultFileIsTheBuiltInDisplay) {
  const DisplayDesign file =
      designFile(std::string(PARALLAX_SOURCE_DIR) + "/displays/default.json");
  const DisplayDesign builtIn = designDisplay(defaultDisplaySpec());
  EXPECT_DOUBLE_EQ(file.slitPeriodMm, builtIn.slitPeriodMm);
  EXPECT_DOUBLE_EQ(file.viewZoneWidthMm, builtIn.viewZoneWidthMm);
  EXPECT_NEAR(file.spec.mask.dutyCycle, builtIn.spec.mask.dutyCycle, 1e-9);
}

TEST(DisplayFile, MeasuredPeriodsGiveTheDistance) {
  const std::string path = writeTemp(
      "measured.json", R"({"gap_mm": 3, "screen_period_px": 9, "slit_period_px": 9.045})");
  const DisplayDesign d = designFile(path);
  EXPECT_NEAR(d.viewDistanceMm, 3.0 / (9.045 / 9.0 - 1.0), 1e-6);
}

TEST(DisplayFile, WrittenTextReadsBackToTheSameDesign) {
  DisplaySpec s = defaultDisplaySpec();
  s.order = LayerOrder::BarrierFront;
  s.gapMm = 4.5;
  s.views = 7.5;
  s.mask.kind = MaskKind::Wiggling;
  s.mask.wiggleAmplitudeMm = 0.3;
  s.mask.wiggleWavelengthMm = 5;
  BarrierCameraSettings camera;
  camera.virtualDistanceMm = kInfinity;
  camera.subpixelRays = true;
  const DisplayDesign a = designDisplay(s, camera);
  const DisplayDesign b = designFile(writeTemp("round.json", displayFileText(s, camera)));
  EXPECT_DOUBLE_EQ(a.slitPeriodMm, b.slitPeriodMm);
  EXPECT_DOUBLE_EQ(a.screenPeriodMm, b.screenPeriodMm);
  EXPECT_EQ(b.spec.order, LayerOrder::BarrierFront);
  EXPECT_EQ(b.spec.mask.kind, MaskKind::Wiggling);
  EXPECT_DOUBLE_EQ(b.spec.mask.wiggleWavelengthMm, 5.0);
  EXPECT_TRUE(std::isinf(b.virtualDistanceMm));
  EXPECT_TRUE(b.camera.subpixelRays);
  EXPECT_FALSE(b.camera.virtualGapMm);
}

// The camera settings a display file carries reach the description, not the display's spec.
TEST(DisplayFile, DescriptionCarriesTheCameraSettings) {
  const std::string path = writeTemp(
      "camera.json", R"({"subpixel_rays": true, "virtual": {"gap_mm": 6, "distance_mm": 900}})");
  const DisplayDescription d = loadDisplayDescription(path);
  EXPECT_EQ(d.kind, DisplayKind::Barrier);
  EXPECT_TRUE(d.camera.subpixelRays);
  EXPECT_EQ(d.camera.virtualGapMm, 6.0);
  EXPECT_EQ(d.camera.virtualDistanceMm, 900.0);
  EXPECT_EQ(d.barrier.source, path);
  const BarrierDisplayFile file = loadDisplayFile(path);
  EXPECT_EQ(displayFileText(file.spec, file.camera), displayFileText(d.barrier, d.camera));
  const std::string text = displayFileText(file.spec, file.camera);
  EXPECT_NE(text.find("\"gap_mm\": 6"), std::string::npos) << text;
  EXPECT_NE(displayFileText(file.spec).find("\"subpixel_rays\": false"), std::string::npos);
  EXPECT_FALSE(loadDisplayDescription("").camera.subpixelRays);
}

void expectError(const std::string& text, const std::string& pointer) {
  const std::string path = writeTemp("bad.json", text);
  try {
    designFile(path);
    ADD_FAILURE() << "accepted " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.path(), pointer) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
  }
}

TEST(DisplayFile, ErrorsNameTheFileAndTheKey) {
  expectError(R"({"gap_mm": 0})", "/gap_mm");
  expectError(R"({"gapmm": 3})", "/gapmm");
  expectError(R"({"gap_mm": "three"})", "/gap_mm");
  expectError(R"({"image_layer": {"resolution": [1920]}})", "/image_layer/resolution");
  expectError(R"({"mask": {"type": "zigzag"}})", "/mask/type");
  expectError(R"({"virtual": {"distance_mm": "far"}})", "/virtual/distance_mm");
  expectError(R"({"views": 1})", "/views");
  expectError(R"({"layer_order": "sideways"})", "/layer_order");
  expectError(R"({"screen_period_px": 9, "slit_period_px": 8})", "/slit_period_px");
  expectError(R"({"mask": {"type": "pinholes"}})", "/mask/vertical_period_px");
}

// One loader for every kind: told apart by content, presets by name, the built-in barrier for "".
TEST(DisplayDescription, ToldApartByContent) {
  const std::string barrier = writeTemp("described-barrier.json", R"({"gap_mm": 4, "views": 7})");
  const std::string visual =
      writeTemp("described-visual.json", R"({"pitch": {"value": 50}, "slope": {"value": -7},
    "center": {"value": 0.5}, "viewCone": {"value": 40}, "invView": {"value": 1},
    "DPI": {"value": 324}, "screenW": {"value": 1536}, "screenH": {"value": 2048}})");
  const DisplayDescription b = loadDisplayDescription(barrier);
  EXPECT_EQ(b.kind, DisplayKind::Barrier);
  EXPECT_EQ(b.barrier.gapMm, 4);
  EXPECT_EQ(b.source(), barrier);
  const DisplayDescription l = loadDisplayDescription(visual);
  EXPECT_EQ(l.kind, DisplayKind::Lenticular);
  EXPECT_EQ(l.lenticular.screenW, 1536);
  EXPECT_EQ(l.source(), visual);
  const DisplayDescription p = loadDisplayDescription("lkg:go");
  EXPECT_EQ(p.kind, DisplayKind::Lenticular);
  EXPECT_EQ(p.lenticular.screenW, 1440);
  EXPECT_EQ(p.lenticular.quilt.columns, 11);
  const DisplayDescription builtIn = loadDisplayDescription("");
  EXPECT_EQ(builtIn.kind, DisplayKind::Barrier);
  EXPECT_EQ(builtIn.barrier.imagePanel.width, defaultDisplaySpec().imagePanel.width);
  // A barrier file with a lenticular key is still a barrier file's error, naming the key.
  writeTemp("described-barrier.json", R"({"gap_mm": 4, "views": 7, "configVersion": "3.0"})");
  try {
    loadDisplayDescription(barrier);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/configVersion: unknown key"), std::string::npos);
  }
  try {
    loadDisplayDescription("lkg:nonesuch");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lkg:nonesuch"), std::string::npos);
  }
}

}  // namespace
}  // namespace parallax
