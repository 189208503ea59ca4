// `parallax interlace`: N ordinary camera views, or one quilt of them, mapped onto the display
// as the usual practice does (the paper's Fig. 2 direct mapping), written as `render` writes
// its layers. Conventions: docs/quilts.md.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/display/barrier_rays.h"
#include "parallax/display/display_model.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/io/lenticular_file.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/render/quilt.h"

namespace parallax::app {

namespace {

struct InterlaceOptions {
  std::vector<std::string> inputs;
  std::string display, quiltLayout, output;
  std::string resampling = "linear";
  bool subpixels = false;
  bool linear = false;
};

// The views given: one quilt (its layout from the name or --quilt-layout) or view files, leftmost
// camera first, all of one size.
std::vector<Image> readViews(const InterlaceOptions& o, QuiltLayout& layout) {
  if (o.inputs.size() == 1) {
    const std::string& path = o.inputs[0];
    if (o.quiltLayout.empty()) {
      layout = parseQuiltName(path);
    } else if (!parseColumnsByRows(o.quiltLayout, layout.columns, layout.rows)) {
      throw InputError("command line", "--quilt-layout",
                       "expected COLUMNSxROWS, got '" + o.quiltLayout + "'");
    }
    return splitQuilt(readImage(path), layout, path);
  }
  if (!o.quiltLayout.empty())
    throw InputError("command line", "--quilt-layout", "applies to a single quilt file");
  std::vector<Image> views;
  for (const std::string& path : o.inputs) {
    views.push_back(readImage(path));
    if (views.back().width() != views[0].width() || views.back().height() != views[0].height())
      throw InputError(path, "",
                       "is " + std::to_string(views.back().width()) + "x" +
                           std::to_string(views.back().height()) + ", the first view " +
                           std::to_string(views[0].width()) + "x" +
                           std::to_string(views[0].height()));
  }
  return views;
}

ViewResampling parseResampling(const std::string& text) {
  if (text == "nearest") return ViewResampling::Nearest;
  if (text == "linear") return ViewResampling::Linear;
  throw InputError("command line", "--view-resampling",
                   "expected nearest or linear, got '" + text + "'");
}

void recordInputs(JsonWriter& record, const InterlaceOptions& o, const QuiltLayout& layout,
                  const std::vector<Image>& views) {
  if (o.inputs.size() == 1) {
    record.set("/inputs/quilt", o.inputs[0]);
    record.set("/inputs/columns", layout.columns);
    record.set("/inputs/rows", layout.rows);
  } else {
    record.set("/inputs/views", o.inputs);
  }
  record.set("/inputs/view_count", int(views.size()));
  record.set("/inputs/view_size",
             std::to_string(views[0].width()) + "x" + std::to_string(views[0].height()));
}

// A lenticular panel: every subpixel takes the views its view fraction lies between, blended,
// as Looking Glass's interlacing shader does (render/quilt.h, interlaceQuiltLenticular).
void runLenticularInterlace(const InterlaceOptions& o, const LenticularCalibration& calibration) {
  if (o.subpixels)
    throw InputError("command line", "--subpixels",
                     "applies to barrier displays; a lenticular panel is interlaced per subpixel");
  const LenticularDesign design = designLenticular(calibration);
  const double w = calibration.screenW, h = calibration.screenH;
  checkMemoryEstimate(imageBytes(w, h, kFloatRgbPixelBytes, 2) + imageBytes(w, h, kRgba8PixelBytes),
                      calibration.source, "the panel image", "use a smaller panel");
  QuiltLayout layout;
  const std::vector<Image> views = readViews(o, layout);
  const Image panel = interlaceQuiltLenticular(design, views);
  JsonWriter record;
  startRenderRecord(record, "interlace", o.display);
  record.set("/display_kind", "lenticular");
  recordInputs(record, o, layout, views);
  record.set("/inputs/view_mapping",
             "each subpixel's view fraction f between views f N - 1/2, blended linearly");
  record.set("/outputs/image", "image.png");
  record.set("/outputs/calibration", "visual.json");
  writeLenticularDesignJson(record, "/design", design);
  OutputSet set(o.output);
  writeImage(set.path("image.png"), panel);
  if (o.linear) writeImage(set.path("image.pfm"), panel);
  writeFileAtomically(set.path("visual.json"), lenticularCalibrationText(calibration));
  writeFileAtomically(set.path("render.json"), record.dump() + "\n");
  set.commit();
  std::printf("wrote %s/image.png (%dx%d) from %zu views, %s/visual.json, %s/render.json\n",
              set.dir().c_str(), panel.width(), panel.height(), views.size(), set.dir().c_str(),
              set.dir().c_str());
}

// "9 views (round(views), views = 9)": what the display takes, for error messages.
std::string viewsNeeded(const DisplayDesign& design) {
  char text[128];
  std::snprintf(text, sizeof text, "%d views (%s, views = %g)", interlacedViewCount(design),
                design.camera.subpixelRays ? "round(3 views) with subpixel rays" : "round(views)",
                design.views);
  return text;
}

void runInterlace(const InterlaceOptions& o) {
  const ViewResampling resampling = parseResampling(o.resampling);
  const DisplayDescription description = loadDisplayOrDefault(o.display);
  if (description.kind == DisplayKind::Lenticular)
    return runLenticularInterlace(o, description.lenticular);
  BarrierCameraSettings camera = description.camera;
  camera.subpixelRays = camera.subpixelRays || o.subpixels;
  const DisplayDesign design = designDisplay(description.barrier, camera);
  checkLayerMemory(design, design.spec.imagePanel.width, 1,
                   o.display.empty() ? "<built-in display>" : o.display);
  QuiltLayout layout;
  std::vector<Image> views = readViews(o, layout);
  const int given = int(views.size()), needed = interlacedViewCount(design);
  if (given != needed) {
    // A standard quilt (48 views) on a 9-view barrier, or the reverse: resampled across views.
    std::fprintf(stderr,
                 "note: %d views given, the display takes %s: resampled across views (%s)\n", given,
                 viewsNeeded(design).c_str(), o.resampling.c_str());
    views = resampleViews(views, needed, resampling);
  }

  const Panel& panel = design.spec.imagePanel;
  if (views[0].width() != panel.width || views[0].height() != panel.height)
    std::fprintf(stderr,
                 "note: resampling the views by area from %dx%d to the image layer's %dx%d\n",
                 views[0].width(), views[0].height(), panel.width, panel.height);
  const Image image = interlaceCameraViews(design, views);

  JsonWriter record;
  startRenderRecord(record, "interlace", o.display);
  recordInputs(record, o, layout, views);
  record.set("/inputs/view_count", given);
  if (given != needed) record.set("/inputs/view_resampling", o.resampling);
  // Camera k (k-th from the left) feeds the design view seen from the k-th eye from the left.
  const std::unique_ptr<DisplayModel> display = makeBarrierDisplay(design);
  const std::vector<int> designView = designViewsLeftToRight(design);
  for (size_t k = 0; k < designView.size(); ++k) {
    const std::string at = "/cameras/" + std::to_string(k);
    const Vec3d eye = display->viewPosition(designView[k]);
    record.set(at + "/design_view", designView[k]);
    record.set(at + "/eye_mm", Vec3f(float(eye.x), float(eye.y), float(eye.z)));
  }
  cliReporter().result(
      writeDisplayLayers(o.output, image, maskLayerImage(design), design, o.linear, record));
}

}  // namespace

void registerInterlaceCommand(CLI::App& cli) {
  auto options = std::make_shared<InterlaceOptions>();
  CLI::App* cmd = cli.add_subcommand(
      "interlace", "Map N camera views (leftmost first) or one quilt onto the display (Fig. 2)");
  cmd->add_option("inputs", options->inputs,
                  "The views as image files, leftmost camera first, or one quilt "
                  "(NAME_qs{C}x{R}a{aspect}.png, tiles from the bottom-left)")
      ->required()
      ->type_name("VIEW... | QUILT");
  cmd->add_option("--display", options->display,
                  "Display file of any kind, or lkg:NAME (built-in display if omitted)");
  cmd->add_option("--view-resampling", options->resampling,
                  "When the views given are not the barrier's count: nearest or linear (blend "
                  "the two views around each needed one)")
      ->capture_default_str();
  cmd->add_option("--quilt-layout", options->quiltLayout,
                  "The quilt's tiles, when its name does not say (no aspect check)")
      ->type_name("CxR");
  cmd->add_option("-o,--output", options->output, "Output folder")->required();
  cmd->add_flag("--subpixels", options->subpixels,
                "Views per R, G, B subpixel column (three times the views)");
  cmd->add_flag("--linear", options->linear, "Also write image.pfm, linear float");
  cmd->callback([options] { runInterlace(*options); });
}

}  // namespace parallax::app
