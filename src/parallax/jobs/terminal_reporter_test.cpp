// The terminal reporter (jobs/terminal_reporter.h): notes and warnings on stderr, results on
// stdout, each {field} spelled by the front end's speller.
#include "parallax/jobs/terminal_reporter.h"

#include <gtest/gtest.h>

#include <string>

namespace parallax::jobs {
namespace {

std::string asOption(const std::string& field) {
  return "--" + field;
}

TEST(TerminalReporter, SpellsFieldsOnTheStreamsOfTheCommandLine) {
  TerminalReporter cli(asOption, true, false);
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  cli.note("use {frames} 1:9");
  cli.warning("beyond the budget; {fit} depth compresses it");
  cli.result("wrote out/image.png");
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err, "note: use --frames 1:9\nwarning: beyond the budget; --fit depth compresses it\n");
  EXPECT_EQ(out, "wrote out/image.png\n");
}

TEST(TerminalReporter, PythonsKeepsTheResults) {
  TerminalReporter python([](const std::string& field) { return field; }, false, false);
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  python.note("use {frames} 1:9");
  python.result("wrote out/image.png");
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "note: use frames 1:9\n");
}

}  // namespace
}  // namespace parallax::jobs
