// The one gate every file reader of io goes through before it opens an input: a clear
// InputError for a missing file, a folder, a device, a FIFO or a socket (which would hang a
// reader or feed it endless bytes), and messages that stay on one line whatever the input
// holds.
#pragma once

#include <string>
#include <string_view>

#include "parallax/core/error.h"

namespace parallax {

// Throws InputError(path, pointer, ...) unless `path` names a regular file (after following
// symbolic links): "file not found", "is a folder, not a file", "not a regular file (a
// character device)", "... (a named pipe (FIFO))", ... `pointer` names the key that gave
// the path, if any.
void requireRegularFile(const std::string& path, const std::string& pointer = "");

// The whole of a regular file (requireRegularFile first); throws InputError if it cannot be
// opened or read.
std::string readInputFile(const std::string& path, const std::string& pointer = "");

// `text` with control characters (newline, tab, ESC, ...) written as \n, \t, \x1b, so that a
// key, value or file name quoted in a message cannot break it over lines or drive a terminal.
std::string escapeControl(std::string_view text);

// An InputError whose file, pointer and message are all passed through escapeControl.
InputError inputError(const std::string& file, const std::string& pointer,
                      const std::string& message);

}  // namespace parallax
