// The `parallax` command line: parses argv, runs the chosen command and turns every failure into
// one line and an exit code (command_line.cpp). main.cpp is only this call, so that the program
// is the app library's and no second file compiles CLI11.
#pragma once

namespace parallax::app {

// Every failure is one line on stderr, "error: <file or option>: <message>": bad input exits
// with 2, anything else with 1. --help and --version print to stdout and exit 0.
int runCommandLine(int argc, char** argv);

}  // namespace parallax::app
