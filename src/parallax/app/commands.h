// The subcommands of `parallax`. Each registers its options on the CLI and its action runs
// after parsing; actions throw InputError for bad input (main turns it into exit code 2).
#pragma once

#include <string>

#include "parallax/app/cli_support.h"
#include "parallax/display/lenticular.h"

namespace CLI {
class App;
}

namespace parallax::app {

// `render` for a lenticular display (and its alias `lenticular render`): the panel's picture,
// one ray per subpixel around its view, written with the calibration beside it.
struct LenticularRenderJob {
  LenticularCalibration calibration;
  std::string scene, output;
  SamplingOptions sampling;
  FilterOptions filter;
  double distance = 0;    // the design viewer's distance in mm; 0: the default
  SceneLoadOptions load;  // --camera
  RgbdCliOptions rgbd;    // --rgbd COLOUR DEPTH instead of the scene (docs/rgbd.md)
};
void runLenticularRender(const LenticularRenderJob& job);

void registerViewCommand(CLI::App& cli);
void registerInfoCommand(CLI::App& cli);
void registerBenchCommand(CLI::App& cli);
void registerDesignCommand(CLI::App& cli);
void registerRenderCommand(CLI::App& cli);
void registerLightfieldCommand(CLI::App& cli);
void registerSimulateCommand(CLI::App& cli);
void registerCalibrateCommand(CLI::App& cli);
void registerInterlaceCommand(CLI::App& cli);
void registerLenticularCommand(CLI::App& cli);
void registerShowCommand(CLI::App& cli);

}  // namespace parallax::app
