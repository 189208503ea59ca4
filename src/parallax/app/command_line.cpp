// The `parallax` command line (command_line.h).
//
// Every failure is one line on stderr, "error: <file or option>: <message>": bad input (an
// InputError, CLI11's own parse errors, and memory that ran out despite the estimates) exits
// with 2, anything else with 1. --help and --version print to stdout and exit 0.
#include "parallax/app/command_line.h"

#include <cstdio>
#include <exception>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "parallax/app/cli_parser.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/cluster/process_group.h"
#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/jobs/limits.h"

namespace {

// One line: newlines (CLI11 joins some lists with them) become "; ".
void printError(std::string message) {
  for (size_t at = message.find('\n'); at != std::string::npos; at = message.find('\n', at))
    message.replace(at, 1, "; ");
  while (!message.empty() && (message.back() == ' ' || message.back() == ';')) message.pop_back();
  std::fprintf(stderr, "error: %s\n", message.c_str());
}

// InputError("command line", "--spp", message) reads "--spp: message": the option is the input.
// A request's field (RequestError, and {field} in any text) is spelled as its option.
std::string inputErrorText(const parallax::InputError& e) {
  const std::string prefix = "command line: ";
  const std::string text = e.what();
  if (e.file() == "command line" && !e.path().empty() && text.rfind(prefix, 0) == 0)
    return text.substr(prefix.size());
  return parallax::app::errorLine(e);
}

}  // namespace

namespace parallax::app {

int runCommandLine(int argc, char** argv) {
  // Under mpirun, the job's ranks (docs/distributed.md); otherwise this process alone.
  parallax::cluster::Session session(argc, argv);
  parallax::cluster::ProcessGroup& group = session.group();
  CommandLine cli{
      "parallax: ray tracing for glasses-free 3-D displays: two-layer parallax barriers and "
      "slanted lenticular (Looking Glass) panels"};
  // The ray tracing library too: Embree 3 or 4, whichever this build runs on.
  cli.versionFlag("--version", [] { return versionText(); });
  Command& program = cli.root();
  program.requireSubcommand(1);
  addLimitOptions(program);
  registerDesignCommand(program);
  registerRenderCommand(program);
  registerViewCommand(program);
  registerSimulateCommand(program);
  registerLightfieldCommand(program);
  registerCalibrateCommand(program);
  registerInterlaceCommand(program);
  registerLenticularCommand(program);
  registerShowCommand(program);
  registerInfoCommand(program);
  registerBenchCommand(program);
  registerSplatsCommand(program);
  // A dry run: the commands that estimate their whole peak stop at the estimate and print it.
  program.addFlag("--estimate", jobs::limits().estimateOnly,
                  "Print the command's estimated peak memory (resident set size) and exit before "
                  "any work; nothing is written (render, view, simulate, lenticular render, show)");
  cli.afterParsing([](const std::string& name) {
    if (!jobs::limits().estimateOnly) return;
    if (name != "render" && name != "view" && name != "simulate" && name != "lenticular render" &&
        name != "show")
      throw InputError("command line", "--estimate",
                       "not available for " + name +
                           "; it is for render, view, simulate, lenticular render and show");
  });
  std::optional<parallax::cluster::Failure> failure;
  const auto fail = [&](int exitCode, const std::string& message) {
    failure = parallax::cluster::Failure{group.rank(), exitCode, message};
  };
  try {
    // --help and --version are printed by rank 0 only.
    const CommandLine::Outcome outcome = cli.parse(argc, argv, group.isRoot());
    if (outcome.kind == CommandLine::Outcome::Kind::Refused) fail(kExitInputError, outcome.message);
  } catch (const parallax::jobs::EstimateOnly& e) {
    // --estimate: rank 0 says what the command would need; nothing was allocated or written.
    if (group.isRoot())
      std::printf("would need about %s (peak resident memory, %.0f bytes) for %s\n",
                  parallax::formatGiB(e.estimate().bytes).c_str(), e.estimate().bytes,
                  parallax::spellFields(e.estimate().what, parallax::app::optionName).c_str());
  } catch (const parallax::cluster::PeerFailed& e) {
    // Another rank failed and said so at a checkpoint: it prints its message; stop quietly.
    return e.failure().exitCode;
  } catch (const parallax::InputError& e) {
    fail(parallax::app::kExitInputError, inputErrorText(e));
  } catch (const std::bad_alloc&) {
    // The estimates missed an allocation: still the input's size, not a bug.
    fail(parallax::app::kExitInputError,
         "out of memory: the input needs more memory than the estimates foresaw; use smaller "
         "sizes, fewer views or fewer eyes");
  } catch (const std::exception& e) {
    fail(1, e.what());
  }
  // Every rank meets here, or a failed one meets the others at their next checkpoint; the
  // lowest failing rank's message is printed once, and every rank exits with its code.
  const std::optional<parallax::cluster::Failure> agreed = group.agree(failure);
  if (!agreed) return 0;
  if (agreed->rank == group.rank()) printError(agreed->message);
  return agreed->exitCode;
}

}  // namespace parallax::app
