// `parallax lightfield`: the two-plane ray space of a stretch of the display (the paper's
// Figs. 7 and 8) as an SVG.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/io/image_file.h"
#include "parallax/sim/lightfield.h"

namespace parallax::app {

void registerLightfieldCommand(CLI::App& cli) {
  struct Options {
    std::string display;
    LightFieldOptions plot;
    std::string output = "out/lightfield.svg";
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = cli.add_subcommand(
      "lightfield", "Plot the display's rays in two-plane (x, v) space as an SVG (Figs. 7, 8)");
  cmd->add_option("display", options->display, "Display file (built-in display if omitted)");
  cmd->add_option("--from", options->plot.fromMm, "Left end of the stretch on the image layer (mm)")
      ->capture_default_str();
  cmd->add_option("--to", options->plot.toMm, "Right end of the stretch (mm)")
      ->capture_default_str();
  cmd->add_option("--row", options->plot.row, "Image row (default: the middle row)");
  cmd->add_option("--spp", options->plot.samplesPerPixel,
                  "Also draw the n x n sub-ray samples of each cell (spp = n*n)");
  cmd->add_option("-o,--output", options->output, "Output SVG")->capture_default_str();
  cmd->callback([options] {
    const DisplayDesign design = loadDesignOrDefault(options->display);
    writeFileAtomically(options->output, lightFieldSvg(design, options->plot));
    std::printf("wrote %s\n", options->output.c_str());
  });
}

}  // namespace parallax::app
