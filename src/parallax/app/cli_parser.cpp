#include "parallax/app/cli_parser.h"

#include <CLI/CLI.hpp>

#include <cstdint>
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
