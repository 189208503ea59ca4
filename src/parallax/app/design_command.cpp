// `parallax design`: the derived design of a display (jobs/design_job.h), as text or JSON.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"
#include "parallax/jobs/design_job.h"

namespace parallax::app {

void registerDesignCommand(Command& cli) {
  struct Options {
    DisplayRequest display;
    std::string scene;
    FramingRequest framing;
    bool json = false;
    double depth = 0.0;
  };
  auto options = std::make_shared<Options>();
  Command* cmd =
      cli.addSubcommand("design", "Print the derived design of a display (barrier or lenticular)");
  addDisplayOption(*cmd, options->display,
                   "Display file of any kind, or lkg:NAME (built-in display if omitted)",
                   "display");
  cmd->addOption("--depth", options->depth,
                 "Depth (mm, + toward the viewer) for the disparity figure; default: the depth "
                 "of field")
      ->check(realIn(-kInfinity, kInfinity));
  cmd->addFlag("--json", options->json, "Print one JSON object");
  cmd->addOption("--scene", options->scene,
                 "Also frame this scene for the display as render does: its depth range "
                 "against the depth of field");
  addFramingOptions(*cmd, options->framing, "With --scene: ");
  cmd->callback([options] {
    DesignRequest request;
    request.display = options->display;
    request.depth = options->depth;
    if (!options->scene.empty()) {
      request.scene = SceneRequest{};
      request.scene->path = options->scene;
      request.scene->load.import = importOptions();
    }
    request.framing = options->framing;
    const DesignReport report = jobs::designReport(request, cliReporter());
    // The text's own warning line goes to stdout with the figures, as it always has.
    std::fputs(spellFields(options->json ? report.json + "\n" : report.text, optionName).c_str(),
               stdout);
  });
}

}  // namespace parallax::app
