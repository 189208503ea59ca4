// The subcommands of `parallax`. Each registers its options on the CLI and its action runs
// after parsing; actions throw InputError for bad input (main turns it into exit code 2).
#pragma once

#include <string>

#include "parallax/app/cli_support.h"

namespace CLI {
class App;
}

namespace parallax::app {

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
