// Shared by the fuzz targets (fuzz_*.cpp): a private scratch folder per process, writing the
// input to a file there for the io functions that take paths, and the one rule every target
// follows: parallax::InputError is a clean refusal of bad input; any other exception escaping
// the parser is a finding, so it is left to escape (std::terminate -> abort, which libFuzzer
// and fuzz_replay report).
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "parallax/core/error.h"

namespace parallax::fuzz {

namespace fs = std::filesystem;

// The scratch folder of this process (created on first use, removed at exit).
inline const fs::path& scratchDir() {
  static const fs::path dir = [] {
    const char* base = std::getenv("PARALLAX_FUZZ_TMP");
    fs::path d = (base && *base) ? fs::path(base) : fs::temp_directory_path();
    d /= "parallax-fuzz-" + std::to_string(::getpid());
    fs::create_directories(d);
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(scratchDir(), ignored);
    });
    return d;
  }();
  return dir;
}

// Writes `bytes` to `name` inside the scratch folder and returns the file's path.
inline std::string writeScratch(const std::string& name, std::string_view bytes) {
  const fs::path path = scratchDir() / name;
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  out.close();
  if (!out) std::abort();  // the harness itself failed (disk full?): never a silent pass
  return path.string();
}

inline std::string_view asText(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Splits `text` at the first `separator` line into (before, after); after is empty if absent.
inline std::pair<std::string_view, std::string_view> splitAt(std::string_view text,
                                                             std::string_view separator) {
  const size_t at = text.find(separator);
  if (at == std::string_view::npos) return {text, {}};
  return {text.substr(0, at), text.substr(at + separator.size())};
}

// Runs `parse`; InputError is the expected refusal and is swallowed, anything else escapes.
// PARALLAX_FUZZ_VERBOSE=1 prints the refusals (to check that seeds are accepted).
template <typename F>
int refuseCleanly(F&& parse) {
  static const bool verbose = std::getenv("PARALLAX_FUZZ_VERBOSE") != nullptr;
  try {
    parse();
    if (verbose) std::fprintf(stderr, "  accepted\n");
  } catch (const InputError& e) {
    if (verbose) std::fprintf(stderr, "  refused: %s\n", e.what());
  }
  return 0;
}

}  // namespace parallax::fuzz
