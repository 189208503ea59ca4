// The subcommands of `parallax`. Each registers its options on the CLI and its action runs
// after parsing; actions throw InputError for bad input (main turns it into exit code 2).
#pragma once

#include <string>

#include "parallax/app/cli_support.h"

namespace parallax::app {

void registerViewCommand(Command& cli);
void registerInfoCommand(Command& cli);
void registerBenchCommand(Command& cli);
void registerDesignCommand(Command& cli);
void registerRenderCommand(Command& cli);
void registerLightfieldCommand(Command& cli);
void registerSimulateCommand(Command& cli);
void registerCalibrateCommand(Command& cli);
void registerInterlaceCommand(Command& cli);
void registerLenticularCommand(Command& cli);
void registerShowCommand(Command& cli);
void registerSplatsCommand(Command& cli);

}  // namespace parallax::app
