// parallax: renders 3-D scenes into the layer images of two-LCD parallax-barrier displays.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"

int main(int argc, char** argv) {
  CLI::App cli{"parallax: ray tracing for two-layer parallax-barrier 3-D displays"};
  cli.set_version_flag("--version", std::string("parallax ") + PARALLAX_VERSION_STRING);
  cli.require_subcommand(1);
  parallax::app::registerDesignCommand(cli);
  parallax::app::registerRenderCommand(cli);
  parallax::app::registerViewCommand(cli);
  parallax::app::registerSimulateCommand(cli);
  parallax::app::registerLightfieldCommand(cli);
  parallax::app::registerCalibrateCommand(cli);
  parallax::app::registerInterlaceCommand(cli);
  parallax::app::registerLenticularCommand(cli);
  parallax::app::registerInfoCommand(cli);
  parallax::app::registerBenchCommand(cli);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : parallax::app::kExitInputError;
  } catch (const parallax::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return parallax::app::kExitInputError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
