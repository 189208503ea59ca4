#include "parallax/jobs/terminal_reporter.h"

#include <unistd.h>

#include <cstdio>

#include "parallax/core/error.h"

namespace parallax::jobs {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)),
      enabled_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      lastDraw_(start_) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fputs("\r\033[K", stderr);
}

void ProgressBar::update(int done, int total) {
  if (!enabled_ || total <= 0) return;
  const std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (done < total && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  lastDraw_ = now;
  drawn_ = true;
  const double fraction = double(done) / double(total);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double remaining = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
  constexpr int kWidth = 30;
  const int filled = int(fraction * kWidth);
  std::string bar(size_t(filled), '#');
  bar.append(size_t(kWidth - filled), '-');
  std::fprintf(stderr, "\r%s [%s] %3d%%  %.1fs left%s%s\033[K", label_.c_str(), bar.c_str(),
               int(fraction * 100), remaining, detail_.empty() ? "" : "  ", detail_.c_str());
  std::fflush(stderr);
}

void ProgressBar::detail(const std::string& text) {
  const std::lock_guard lock(mutex_);
  detail_ = text;
}

namespace {

class ProgressBarTask : public Progress {
 public:
  explicit ProgressBarTask(const std::string& label) : bar_(label) {}
  void update(int done, int total) override { bar_.update(done, total); }
  void detail(const std::string& text) override { bar_.detail(text); }

 private:
  ProgressBar bar_;
};

}  // namespace

void TerminalReporter::note(const std::string& text) {
  std::fprintf(stderr, "note: %s\n", spellFields(text, spell_).c_str());
}

void TerminalReporter::warning(const std::string& text) {
  std::fprintf(stderr, "warning: %s\n", spellFields(text, spell_).c_str());
}

void TerminalReporter::result(const std::string& line) {
  if (!results_) return;
  std::printf("%s\n", spellFields(line, spell_).c_str());
  std::fflush(stdout);
}

std::unique_ptr<Progress> TerminalReporter::progress(const std::string& label) {
  if (!progress_) return silentReporter().progress(label);
  return std::make_unique<ProgressBarTask>(label);
}

}  // namespace parallax::jobs
