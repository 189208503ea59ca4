#include "parallax/jobs/reporter.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>

namespace parallax::jobs {

namespace {

class NoProgress : public Progress {
 public:
  void update(int, int) override {}
};

class SilentReporter : public Reporter {
 public:
  void note(const std::string&) override {}
  void warning(const std::string&) override {}
  void result(const std::string&) override {}
  std::unique_ptr<Progress> progress(const std::string&) override {
    return std::make_unique<NoProgress>();
  }
};

}  // namespace

std::unique_ptr<Progress> RecordingReporter::progress(const std::string&) {
  return std::make_unique<NoProgress>();
}

Reporter& silentReporter() {
  static SilentReporter reporter;
  return reporter;
}

std::string printed(const char* format, ...) {
  va_list args;
  va_start(args, format);
  va_list again;
  va_copy(again, args);
  const int size = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  std::string text(size_t(std::max(size, 0)), '\0');
  if (size > 0) std::vsnprintf(text.data(), text.size() + 1, format, again);
  va_end(again);
  return text;
}

}  // namespace parallax::jobs
