// `parallax lightfield`: the two-plane ray space of a stretch of the display (the paper's
// Figs. 7 and 8) as an SVG.
#include <algorithm>
#include <climits>
#include <cstdio>
#include <memory>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"
#include "parallax/core/output_path.h"
#include "parallax/io/image_file.h"
#include "parallax/sim/lightfield.h"

namespace parallax::app {

void registerLightfieldCommand(Command& cli) {
  struct Options {
    DisplayRequest display;
    LightFieldOptions plot;
    std::string output = "out/lightfield.svg";
  };
  auto options = std::make_shared<Options>();
  Command* cmd = cli.addSubcommand(
      "lightfield", "Plot the display's rays in two-plane (x, v) space as an SVG (Figs. 7, 8)");
  addDisplayOption(*cmd, options->display, "Display file (built-in display if omitted)", "display");
  cmd->addOption("--from", options->plot.fromMm, "Left end of the stretch on the image layer (mm)")
      ->captureDefault()
      ->check(realIn(-kInfinity, kInfinity));
  cmd->addOption("--to", options->plot.toMm, "Right end of the stretch (mm), above --from")
      ->captureDefault()
      ->check(realIn(-kInfinity, kInfinity));
  cmd->addOption("--row", options->plot.row,
                 "Image row, 0 to the panel's height - 1 (default: the middle row)")
      ->check(integerIn(0, INT_MAX));
  cmd->addOption("--spp", options->plot.samplesPerPixel,
                 "Also draw the n x n sub-ray samples of each cell (spp = n*n; 0: none)")
      ->check(squareCount(true));
  addLimitOptions(*cmd);
  cmd->addOption("-o,--output", options->output, "Output SVG")->captureDefault();
  cmd->callback([options] {
    const DisplayDesign design = loadDesignOrDefault(options->display.path);
    const LightFieldOptions& plot = options->plot;
    const Panel& panel = design.spec.imagePanel;
    if (!(plot.fromMm < plot.toMm)) throw InputError("--to", "", "must be above --from");
    if (plot.row >= panel.height)
      throw InputError("--row " + std::to_string(plot.row), "",
                       "is off the panel (rows 0 to " + std::to_string(panel.height - 1) + ")");
    // The plot's cells: the film columns of the stretch (at most the panel's), each drawn with
    // its n x n samples; a few hundred bytes of SVG and of ray records apiece.
    const double columnsPerPixel = design.camera.subpixelRays ? 3.0 : 1.0;
    const double columns =
        std::min(panel.width * columnsPerPixel,
                 (plot.toMm - plot.fromMm) / panel.pitchMm * columnsPerPixel + 1);
    constexpr double kBytesPerCell = 400;
    checkMemoryEstimate(columns * (1.0 + plot.samplesPerPixel) * kBytesPerCell,
                        "--spp " + std::to_string(plot.samplesPerPixel), "the plot",
                        "use fewer samples or a shorter stretch");
    checkOutputFile(options->output);  // a folder or an unwritable place: before the plot
    writeFileAtomically(options->output, lightFieldSvg(design, options->plot));
    std::printf("wrote %s\n", options->output.c_str());
  });
}

}  // namespace parallax::app
