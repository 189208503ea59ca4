// parallax: renders 3-D scenes into the layer images of two-LCD parallax-barrier displays.
//
// Every failure is one line on stderr, "error: <file or option>: <message>": bad input (an
// InputError, CLI11's own parse errors, and memory that ran out despite the estimates) exits
// with 2, anything else with 1. --help and --version print to stdout and exit 0.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/core/error.h"

namespace {

// One line: newlines (CLI11 joins some lists with them) become "; ".
void printError(std::string message) {
  for (size_t at = message.find('\n'); at != std::string::npos; at = message.find('\n', at))
    message.replace(at, 1, "; ");
  while (!message.empty() && (message.back() == ' ' || message.back() == ';')) message.pop_back();
  std::fprintf(stderr, "error: %s\n", message.c_str());
}

// InputError("command line", "--spp", message) reads "--spp: message": the option is the input.
std::string inputErrorText(const parallax::InputError& e) {
  const std::string prefix = "command line: ";
  const std::string text = e.what();
  if (e.file() == "command line" && !e.path().empty() && text.rfind(prefix, 0) == 0)
    return text.substr(prefix.size());
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"parallax: ray tracing for two-layer parallax-barrier 3-D displays"};
  cli.set_version_flag("--version", std::string("parallax ") + PARALLAX_VERSION_STRING);
  cli.require_subcommand(1);
  parallax::app::addLimitOptions(cli);
  parallax::app::registerDesignCommand(cli);
  parallax::app::registerRenderCommand(cli);
  parallax::app::registerViewCommand(cli);
  parallax::app::registerSimulateCommand(cli);
  parallax::app::registerLightfieldCommand(cli);
  parallax::app::registerCalibrateCommand(cli);
  parallax::app::registerInterlaceCommand(cli);
  parallax::app::registerLenticularCommand(cli);
  parallax::app::registerShowCommand(cli);
  parallax::app::registerInfoCommand(cli);
  parallax::app::registerBenchCommand(cli);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0: CLI11 prints them.
    if (e.get_exit_code() == 0) return cli.exit(e);
    std::string message = e.what();
    // "parallax frobnicate": CLI11 only says a subcommand is required; name the word.
    const std::vector<std::string> rest = cli.remaining();
    if (e.get_name() == "RequiredError" && !rest.empty())
      message = rest.front() + ": not a command (" + message + ")";
    printError(message);
    return parallax::app::kExitInputError;
  } catch (const parallax::InputError& e) {
    printError(inputErrorText(e));
    return parallax::app::kExitInputError;
  } catch (const std::bad_alloc&) {
    // The estimates missed an allocation: still the input's size, not a bug.
    printError(
        "out of memory: the input needs more memory than the estimates foresaw; use smaller "
        "sizes, fewer views or fewer eyes");
    return parallax::app::kExitInputError;
  } catch (const std::exception& e) {
    printError(e.what());
    return 1;
  }
  return 0;
}
