// Errors in user input. The CLI turns an InputError into one line and exit code 2:
//   <file>: <json path>: <message>
// Library code never prints or exits; it throws these or collects warnings.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace parallax {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string path, const std::string& message)
      : std::runtime_error(format(file, path, message)),
        file_(std::move(file)),
        path_(std::move(path)) {}

  const std::string& file() const { return file_; }
  // JSON pointer of the offending key ("/objects/3/material/color"), or empty.
  const std::string& path() const { return path_; }

 private:
  static std::string format(const std::string& file, const std::string& path,
                            const std::string& message) {
    std::string line = file.empty() ? std::string("<input>") : file;
    if (!path.empty()) line += ": " + path;
    return line + ": " + message;
  }
  std::string file_;
  std::string path_;
};

// A request's field holds a bad value (docs/architecture.md, "Requests"). `field` is the
// request's own name for it ("spp", "depth_budget"); each front end spells it its own way: the
// command line "--spp", Python "spp". `value`, when given, is quoted after the field
// ("--spp 16: needs ...", "spp=16: needs ...").
class RequestError : public InputError {
 public:
  RequestError(std::string field, std::string message, std::string value = {})
      : InputError(kRequestSource, field, message),
        field_(std::move(field)),
        message_(std::move(message)),
        value_(std::move(value)) {}
  static constexpr const char* kRequestSource = "request";

  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }
  const std::string& value() const { return value_; }

 private:
  std::string field_, message_, value_;
};

// Messages, notes and warnings below the front ends name other fields as {field} ("needs
// {layers} nmf"); a front end replaces each by its own spelling before it shows the text.
// Only {name} with name of lower-case letters, digits and '_' is a field; other braces stay.
std::string spellFields(const std::string& text,
                        const std::function<std::string(const std::string& field)>& spell);

// The one line a front end shows for an InputError: "FIELD: message" (RequestError; FIELD as
// `spell` writes it, then " value" or what `withValue` makes of both), "/path: message" for an
// InputError whose file is kRequestSource (a description the request made, such as a display
// with measured periods, refused under its file's key), otherwise "file: /path: message";
// fields in the text spelled.
std::string errorText(const InputError& error,
                      const std::function<std::string(const std::string& field)>& spell,
                      const std::function<std::string(const std::string& field,
                                                      const std::string& value)>& withValue);

}  // namespace parallax
