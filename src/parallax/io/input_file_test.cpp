// The input gate against the file system's own answers: a regular file passes (through a
// symbolic link too), and a missing path, a folder, a character device and a FIFO are refused
// with their kind named, before anything is read; control characters are escaped.
#include "parallax/io/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace parallax {
namespace {

namespace fs = std::filesystem;

std::string refusal(const std::string& path) {
  try {
    requireRegularFile(path, "/objects/0/file");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InputFile, RegularFilesPassAndEverythingElseIsRefusedByKind) {
  const fs::path dir = fs::temp_directory_path() / ("parallax-input-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "scene.json", link = dir / "link.json", fifo = dir / "pipe";
  std::ofstream(file) << "{}";
  fs::create_symlink(file, link);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);

  EXPECT_NO_THROW(requireRegularFile(file.string()));
  EXPECT_NO_THROW(requireRegularFile(link.string()));
  EXPECT_EQ(readInputFile(file.string()), "{}");
  EXPECT_NE(refusal((dir / "missing.json").string()).find("not found"), std::string::npos);
  EXPECT_NE(refusal(dir.string()).find("folder"), std::string::npos);
  EXPECT_NE(refusal("/dev/zero").find("character device"), std::string::npos);
  const std::string pipe = refusal(fifo.string());
  EXPECT_NE(pipe.find("FIFO"), std::string::npos) << pipe;
  EXPECT_NE(pipe.find("/objects/0/file"), std::string::npos) << pipe;  // the key is named
  fs::remove_all(dir);
}

TEST(InputFile, ControlCharactersAreEscaped) {
  EXPECT_EQ(escapeControl("a\nb\tc\x1b"), "a\\nb\\tc\\x1b");
  const std::string message = inputError("f\n.json", "/ke\ny", "bad\rvalue").what();
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_EQ(message.find('\r'), std::string::npos);
}

}  // namespace
}  // namespace parallax
