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
#include "parallax/app/layer_output.h"
#include "parallax/core/error.h"
#include "parallax/display/barrier_rays.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/render/quilt.h"
#include "parallax/sim/simulator.h"  // maskLayerImage

namespace parallax::app {

namespace {

struct InterlaceOptions {
  std::vector<std::string> inputs;
  std::string display, quiltLayout, output;
  bool subpixels = false;
  bool linear = false;
};

// "9 views (round(views), views = 9)": what the display takes, for error messages.
std::string viewsNeeded(const DisplayDesign& design) {
  char text[128];
  std::snprintf(text, sizeof text, "%d views (%s, views = %g)", interlacedViewCount(design),
                design.spec.subpixelRays ? "round(3 views) with subpixel rays" : "round(views)",
                design.views);
  return text;
}

std::vector<Image> readQuiltViews(const InterlaceOptions& o, const DisplayDesign& design,
                                  QuiltLayout& layout) {
  const std::string& path = o.inputs[0];
  if (o.quiltLayout.empty()) {
    layout = parseQuiltName(path);
  } else if (!parseColumnsByRows(o.quiltLayout, layout.columns, layout.rows)) {
    throw InputError("command line", "--quilt-layout",
                     "expected COLUMNSxROWS, got '" + o.quiltLayout + "'");
  }
  if (layout.views() != interlacedViewCount(design))
    throw InputError(path, "",
                     "the quilt holds " + std::to_string(layout.columns) + "x" +
                         std::to_string(layout.rows) + " = " + std::to_string(layout.views()) +
                         " views, the display needs " + viewsNeeded(design));
  return splitQuilt(readImage(path), layout, path);
}

std::vector<Image> readViewFiles(const InterlaceOptions& o, const DisplayDesign& design) {
  if (!o.quiltLayout.empty())
    throw InputError("command line", "--quilt-layout", "applies to a single quilt file");
  if (int(o.inputs.size()) != interlacedViewCount(design))
    throw InputError(
        "command line", "",
        std::to_string(o.inputs.size()) + " views given, the display needs " + viewsNeeded(design));
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

void runInterlace(const InterlaceOptions& o) {
  DisplayDesign design = loadDesignOrDefault(o.display);
  if (o.subpixels) {
    DisplaySpec spec = design.spec;
    spec.subpixelRays = true;
    design = designDisplay(spec);
  }
  checkLayerMemory(design, design.spec.imagePanel.width, 1,
                   o.display.empty() ? "<built-in display>" : o.display);
  const bool fromQuilt = o.inputs.size() == 1;
  QuiltLayout layout;
  const std::vector<Image> views =
      fromQuilt ? readQuiltViews(o, design, layout) : readViewFiles(o, design);

  const Panel& panel = design.spec.imagePanel;
  if (views[0].width() != panel.width || views[0].height() != panel.height)
    std::fprintf(stderr,
                 "note: resampling the views by area from %dx%d to the image layer's %dx%d\n",
                 views[0].width(), views[0].height(), panel.width, panel.height);
  const Image image = interlaceCameraViews(design, views);

  JsonWriter record;
  startRenderRecord(record, "interlace", o.display);
  if (fromQuilt) {
    record.set("/inputs/quilt", o.inputs[0]);
    record.set("/inputs/columns", layout.columns);
    record.set("/inputs/rows", layout.rows);
  } else {
    record.set("/inputs/views", o.inputs);
  }
  record.set("/inputs/view_size",
             std::to_string(views[0].width()) + "x" + std::to_string(views[0].height()));
  // Camera k (k-th from the left) feeds the design view seen from the k-th eye from the left.
  const BarrierRayGenerator rays(design);
  const std::vector<int> designView = designViewsLeftToRight(design);
  for (size_t k = 0; k < designView.size(); ++k) {
    const std::string at = "/cameras/" + std::to_string(k);
    const Vec3d eye = rays.viewPosition(designView[k]);
    record.set(at + "/design_view", designView[k]);
    record.set(at + "/eye_mm", Vec3f(float(eye.x), float(eye.y), float(eye.z)));
  }
  writeDisplayLayers(o.output, image, maskLayerImage(design), design, o.linear, record);
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
  cmd->add_option("--display", options->display, "Display file (built-in display if omitted)");
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
