// `parallax interlace`: N ordinary camera views, or one quilt of them, mapped onto the display
// as the usual practice does (the paper's Fig. 2 direct mapping), written as `render` writes
// its layers. Conventions: docs/quilts.md; the work: jobs/interlace_job.h.
#include <memory>
#include <string>
#include <vector>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"
#include "parallax/jobs/interlace_job.h"
#include "parallax/render/quilt.h"

namespace parallax::app {

namespace {

// The request, and what the command line spells as text: the inputs (one quilt or the views)
// and the quilt's CxR.
struct InterlaceOptions {
  InterlaceRequest request;
  std::vector<std::string> inputs;
  std::string quiltLayout;
};

void runInterlace(InterlaceOptions o) {
  InterlaceRequest& r = o.request;
  if (o.inputs.size() == 1)
    r.quilt = o.inputs[0];
  else
    r.views = o.inputs;
  if (!o.quiltLayout.empty()) {
    QuiltLayout layout;
    if (!parseColumnsByRows(o.quiltLayout, layout.columns, layout.rows))
      throw InputError("command line", "--quilt-layout",
                       "expected COLUMNSxROWS, got '" + o.quiltLayout + "'");
    r.quiltLayout = layout;
  }
  jobs::runInterlace(r, cliReporter());
}

}  // namespace

void registerInterlaceCommand(Command& cli) {
  auto options = std::make_shared<InterlaceOptions>();
  InterlaceRequest& request = options->request;
  Command* cmd = cli.addSubcommand(
      "interlace", "Map N camera views (leftmost first) or one quilt onto the display (Fig. 2)");
  cmd->addOption("inputs", options->inputs,
                 "The views as image files, leftmost camera first, or one quilt "
                 "(NAME_qs{C}x{R}a{aspect}.png, tiles from the bottom-left)")
      ->required()
      ->typeName("VIEW... | QUILT");
  addDisplayOption(*cmd, request.display,
                   "Display file of any kind, or lkg:NAME (built-in display if omitted)");
  cmd->addOption("--view-resampling", request.viewResampling,
                 "Views between the given ones: nearest or linear (blend the two around "
                 "each needed one); for a barrier when the views are not its count, for a "
                 "lenticular panel at every subpixel")
      ->captureDefault();
  cmd->addOption("--quilt-layout", options->quiltLayout,
                 "The quilt's tiles, when its name does not say")
      ->typeName("CxR");
  addLensReadingOptions(*cmd, request.display.lens, true);
  cmd->addOption("-o,--output", request.output, "Output folder")->required();
  cmd->addFlag("--subpixels", request.display.subpixels,
               "Views per R, G, B subpixel column (three times the views)");
  cmd->addFlag("--linear", request.linear, "Also write image.pfm, linear float");
  cmd->callback([options] { runInterlace(*options); });
}

}  // namespace parallax::app
