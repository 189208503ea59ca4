// Errors in user input. The CLI turns an InputError into one line and exit code 2:
//   <file>: <json path>: <message>
// Library code never prints or exits; it throws these or collects warnings.
#pragma once

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

}  // namespace parallax
