#include "parallax/app/cli_parser.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace parallax::app {

Option* Option::check(const TextCheck& check) {
  const auto text = check.check;
  option_->check(
      CLI::Validator([text](std::string& value) { return text(value); }, check.typeName));
  return this;
}

Option* Option::oneOf(const std::vector<std::string>& values) {
  option_->check(CLI::IsMember(values));
  return this;
}

Option* Option::typeName(const std::string& name) {
  option_->type_name(name);
  return this;
}

Option* Option::captureDefault() {
  option_->capture_default_str();
  return this;
}

Option* Option::needs(Option* other) {
  option_->needs(other->option_);
  return this;
}

Option* Option::excludes(Option* other) {
  option_->excludes(other->option_);
  return this;
}

Option* Option::required() {
  option_->required();
  return this;
}

Option* Option::expected(int count) {
  option_->expected(count);
  return this;
}

Option* Command::keep(CLI::Option* option) {
  return &options_.emplace_back(option);
}

Command* Command::addSubcommand(const std::string& name, const std::string& description) {
  return &subcommands_.emplace_back(*app_->add_subcommand(name, description));
}

template <typename T>
Option* Command::addOption(const std::string& name, T& target, const std::string& help) {
  return keep(app_->add_option(name, target, help));
}

template <typename T>
Option* Command::addOptionFunction(const std::string& name, std::function<void(const T&)> onValue,
                                   const std::string& help) {
  return keep(app_->add_option_function<T>(name, std::move(onValue), help));
}

Option* Command::addFlag(const std::string& name, bool& target, const std::string& help) {
  return keep(app_->add_flag(name, target, help));
}

void Command::callback(std::function<void()> action) {
  app_->callback(std::move(action));
}

void Command::requireSubcommand(int count) {
  app_->require_subcommand(count);
}

bool Command::hasOption(const std::string& name) const {
  return app_->get_option_no_throw(name) != nullptr;
}

namespace {

CommandLine::Outcome refusedOrPrinted(CLI::App& app, const CLI::ParseError& e, bool print) {
  // --help and --version are "errors" with exit code 0: CLI11 prints them.
  if (e.get_exit_code() == 0) {
    if (print) app.exit(e);
    return {CommandLine::Outcome::Kind::Printed, {}};
  }
  std::string message = e.what();
  // "parallax frobnicate": CLI11 only says a subcommand is required; name the word.
  const std::vector<std::string> rest = app.remaining();
  if (e.get_name() == "RequiredError" && !rest.empty())
    message = rest.front() + ": not a command (" + message + ")";
  return {CommandLine::Outcome::Kind::Refused, message};
}

}  // namespace

CommandLine::CommandLine(const std::string& description)
    : app_(std::make_unique<CLI::App>(description)), root_(std::make_unique<Command>(*app_)) {}

CommandLine::~CommandLine() = default;

void CommandLine::versionFlag(const std::string& name, std::function<std::string()> text) {
  app_->set_version_flag(name, std::move(text));
}

void CommandLine::afterParsing(std::function<void(const std::string& chosen)> check) {
  CLI::App* app = app_.get();
  app_->parse_complete_callback([app, check = std::move(check)] {
    std::string chosen;
    for (const CLI::App* c = app->get_subcommands().empty() ? nullptr : app->get_subcommands()[0];
         c; c = c->get_subcommands().empty() ? nullptr : c->get_subcommands()[0])
      chosen += (chosen.empty() ? "" : " ") + c->get_name();
    check(chosen);
  });
}

CommandLine::Outcome CommandLine::parse(int argc, const char* const* argv, bool print) {
  try {
    app_->parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return refusedOrPrinted(*app_, e, print);
  }
  return {};
}

CommandLine::Outcome CommandLine::parse(const std::string& arguments, bool print) {
  try {
    app_->parse(arguments, false);
  } catch (const CLI::ParseError& e) {
    return refusedOrPrinted(*app_, e, print);
  }
  return {};
}

// The targets the commands parse into: one instantiation each, here, where CLI11 is.
template Option* Command::addOption(const std::string&, std::string&, const std::string&);
template Option* Command::addOption(const std::string&, std::vector<std::string>&,
                                    const std::string&);
template Option* Command::addOption(const std::string&, double&, const std::string&);
template Option* Command::addOption(const std::string&, float&, const std::string&);
template Option* Command::addOption(const std::string&, int&, const std::string&);
template Option* Command::addOption(const std::string&, int64_t&, const std::string&);
template Option* Command::addOption(const std::string&, uint64_t&, const std::string&);
template Option* Command::addOption(const std::string&, std::optional<double>&, const std::string&);
template Option* Command::addOption(const std::string&, std::optional<float>&, const std::string&);
template Option* Command::addOption(const std::string&, std::optional<int>&, const std::string&);
template Option* Command::addOptionFunction(const std::string&, std::function<void(const double&)>,
                                            const std::string&);
template Option* Command::addOptionFunction(const std::string&, std::function<void(const int&)>,
                                            const std::string&);

}  // namespace parallax::app
