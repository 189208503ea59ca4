// The reporter of a front end on a terminal: notes and warnings on stderr ("note: ...",
// "warning: ..."), result lines on stdout, a progress bar on stderr when it is a terminal; each
// text's {field}s spelled by the front end (the CLI's options, Python's keywords).
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "parallax/jobs/reporter.h"

namespace parallax::jobs {

// A progress bar on stderr, drawn only when stderr is a terminal; thread-safe and throttled.
class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  void update(int done, int total);
  void detail(const std::string& text);

 private:
  std::string label_, detail_;
  bool enabled_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, lastDraw_;
  bool drawn_ = false;
};

class TerminalReporter : public Reporter {
 public:
  using Speller = std::function<std::string(const std::string& field)>;
  // `results`: print result lines (the CLI) or keep them (Python returns its results);
  // `progress`: draw progress bars.
  TerminalReporter(Speller spell, bool results, bool progress)
      : spell_(std::move(spell)), results_(results), progress_(progress) {}
  void note(const std::string& text) override;
  void warning(const std::string& text) override;
  void result(const std::string& line) override;
  std::unique_ptr<Progress> progress(const std::string& label) override;

 private:
  Speller spell_;
  bool results_, progress_;
};

}  // namespace parallax::jobs
