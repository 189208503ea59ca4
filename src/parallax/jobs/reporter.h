// How a runner talks to the person who asked (docs/architecture.md, "Requests"): notes and
// warnings, the result lines (what was written, how fast), and the progress of long steps. The
// command line prints them (notes and warnings on stderr, results on stdout, a progress bar on a
// terminal); Python prints the notes and warnings of loading, design and render on stderr and
// keeps the rest quiet. Texts may name request fields as {field}
// (core/error.h, spellFields): the front end spells them.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace parallax::jobs {

// One long step's progress: update(done, total) from any thread, until it is destroyed.
class Progress {
 public:
  virtual ~Progress() = default;
  virtual void update(int done, int total) = 0;
  // A short status shown beside the bar from the next update on (a solver's objective).
  virtual void detail(const std::string& text) { (void)text; }
  // As the library's progress callbacks take it.
  std::function<void(int, int)> callback() {
    return [this](int done, int total) { update(done, total); };
  }
};

class Reporter {
 public:
  virtual ~Reporter() = default;
  virtual void note(const std::string& text) = 0;
  virtual void warning(const std::string& text) = 0;
  virtual void result(const std::string& line) = 0;
  virtual std::unique_ptr<Progress> progress(const std::string& label) = 0;
};

// Says nothing.
Reporter& silentReporter();

// Keeps what was said, in order (tests; Python hands the warnings on).
class RecordingReporter : public Reporter {
 public:
  std::vector<std::string> notes, warnings, results;
  void note(const std::string& text) override { notes.push_back(text); }
  void warning(const std::string& text) override { warnings.push_back(text); }
  void result(const std::string& line) override { results.push_back(line); }
  std::unique_ptr<Progress> progress(const std::string& label) override;
};

// printf into a string, for result lines.
std::string printed(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace parallax::jobs
