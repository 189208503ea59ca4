// The command-line parser as the commands see it: commands, their options, the checks of an
// option's text, and the program's command line that parses them. CLI11 is behind it, included
// by cli_parser.cpp alone: Debian 12's CLI11 (2.1) is header-only, and its header cost every
// file that included it about 4 s of compiling (docs/install.md, "Compile time").
//
// The names follow CLI11's meaning one for one (addOption is add_option, captureDefault is
// capture_default_str, ...), so its documentation describes what each does.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace parallax::app {

// A check of an option's text (CLI11's Validator): `check` returns the empty string when the
// text is good, else what is wrong with it; `typeName` is what --help shows for the value.
struct TextCheck {
  std::function<std::string(const std::string&)> check;
  std::string typeName;
};

// One option of a command. Each setter returns the option, to be chained.
class Option {
 public:
  explicit Option(CLI::Option* option) : option_(option) {}
  Option* check(const TextCheck& check);
  // The value must be one of `values` (CLI11's IsMember).
  Option* oneOf(const std::vector<std::string>& values);
  Option* typeName(const std::string& name);
  // --help shows the target's value before parsing as the default.
  Option* captureDefault();
  // Refused (not ignored) unless `other` is given too; refused together with `other`.
  Option* needs(Option* other);
  Option* excludes(Option* other);
  Option* required();
  // How many values the option takes (2: --rgbd COLOUR DEPTH).
  Option* expected(int count);

 private:
  CLI::Option* option_;
};

// A command (or the program itself): its options, flags, subcommands and the action run after
// parsing. Owns the Option and Command objects it hands out; CLI11 owns what they stand for.
class Command {
 public:
  // The command `app` is (CommandLine's root, a subcommand).
  explicit Command(CLI::App& app) : app_(&app) {}
  Command(const Command&) = delete;
  Command& operator=(const Command&) = delete;

  Command* addSubcommand(const std::string& name, const std::string& description);
  // An option that parses into `target` (the types the commands use: cli_parser.cpp).
  template <typename T>
  Option* addOption(const std::string& name, T& target, const std::string& help);
  // An option whose parsed value is handed to `onValue` (only when given).
  template <typename T>
  Option* addOptionFunction(const std::string& name, std::function<void(const T&)> onValue,
                            const std::string& help);
  Option* addFlag(const std::string& name, bool& target, const std::string& help);
  // Run after a successful parse when this command was chosen.
  void callback(std::function<void()> action);
  void requireSubcommand(int count);
  // Whether an option of that name (or one of its names) was added already.
  bool hasOption(const std::string& name) const;

 private:
  Option* keep(CLI::Option* option);

  CLI::App* app_;
  std::deque<Option> options_;
  std::deque<Command> subcommands_;
};

// A whole command line: the root command (the program), parsed from the arguments, which runs the
// chosen command's action. Exceptions the actions throw pass through parse().
class CommandLine {
 public:
  explicit CommandLine(const std::string& description = "");
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  Command& root() { return *root_; }
  // `name` prints `text()` and stops, as --help does.
  void versionFlag(const std::string& name, std::function<std::string()> text);
  // Run after the whole line parsed and before any action, with the chosen command's words
  // ("lenticular render").
  void afterParsing(std::function<void(const std::string& chosen)> check);

  // What parse() did: ran the chosen command's action, printed --help or --version (printed
  // only when parse was told to print), or refused the line (`message`: one line's text).
  struct Outcome {
    enum class Kind { Ran, Printed, Refused } kind = Kind::Ran;
    std::string message;
  };
  Outcome parse(int argc, const char* const* argv, bool print = true);
  // The arguments as one string, split at spaces (tests).
  Outcome parse(const std::string& arguments, bool print = true);

 private:
  std::unique_ptr<CLI::App> app_;
  std::unique_ptr<Command> root_;
};

}  // namespace parallax::app
