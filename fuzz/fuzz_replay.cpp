// Replays saved inputs through the fuzz targets without libFuzzer, in any build (the normal
// GCC build registers it with CTest as fuzz_regressions):
//   fuzz_replay DIR...
// Each DIR is either one target's folder (named after the target, e.g. regressions/fuzz_ply)
// or a folder of such folders. Every regular file in it is passed to that target's
// LLVMFuzzerTestOneInput, renamed per target at compile time (fuzz/CMakeLists.txt). A finding
// aborts (an escaping exception ends in std::terminate), which fails the test.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#define PARALLAX_FUZZ_TARGET(name) extern "C" int parallax_##name(const uint8_t*, size_t);
#include "fuzz_targets.inc"
#undef PARALLAX_FUZZ_TARGET

namespace {

namespace fs = std::filesystem;

struct Target {
  const char* name;
  int (*run)(const uint8_t*, size_t);
};

const Target kTargets[] = {
#define PARALLAX_FUZZ_TARGET(name) {#name, parallax_##name},
#include "fuzz_targets.inc"
#undef PARALLAX_FUZZ_TARGET
};

const Target* findTarget(const std::string& name) {
  for (const Target& t : kTargets)
    if (name == t.name) return &t;
  return nullptr;
}

std::vector<fs::path> filesIn(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename().string().front() != '.')
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Replays one target's folder; returns the number of inputs.
size_t replay(const Target& target, const fs::path& dir) {
  size_t count = 0;
  for (const fs::path& file : filesIn(dir)) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    std::fprintf(stderr, "%s: %s (%zu bytes)\n", target.name, file.string().c_str(), bytes.size());
    std::fflush(stderr);
    target.run(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    ++count;
  }
  return count;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s DIR...  (a target's folder, or a folder of them)\n", argv[0]);
    return 2;
  }
  size_t total = 0;
  for (int i = 1; i < argc; ++i) {
    const fs::path dir(argv[i]);
    if (!fs::is_directory(dir)) {
      std::fprintf(stderr, "fuzz_replay: not a folder: %s\n", argv[i]);
      return 2;
    }
    if (const Target* target = findTarget(dir.filename().string())) {
      total += replay(*target, dir);
      continue;
    }
    std::vector<fs::path> subdirs;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
      if (e.is_directory()) subdirs.push_back(e.path());
    std::sort(subdirs.begin(), subdirs.end());
    for (const fs::path& sub : subdirs) {
      const Target* target = findTarget(sub.filename().string());
      if (!target) {
        std::fprintf(stderr, "fuzz_replay: no target named %s\n", sub.string().c_str());
        return 2;
      }
      total += replay(*target, sub);
    }
  }
  std::printf("fuzz_replay: %zu inputs replayed, no findings\n", total);
  return 0;
}
