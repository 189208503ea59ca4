#include "parallax/core/output_path.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "parallax/core/error.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

class OutputPath : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("parallax_output_path_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string at(const std::string& name) const { return (dir_ / name).string(); }
  static void write(const std::string& path) { std::ofstream(path) << "x"; }
  // The PID of a child that has exited and been reaped: a process that no longer runs.
  static long deadPid() {
    const pid_t child = fork();
    if (child == 0) _exit(0);
    int status = 0;
    waitpid(child, &status, 0);
    return long(child);
  }
  // The message of the InputError `check` throws, or "" if it throws none.
  template <typename Check>
  static std::string refusal(Check check) {
    try {
      check();
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(OutputPath, TemporaryOwnerReadsOnlyItsOwnForm) {
  EXPECT_EQ(temporaryOwner("image.png.tmp-1234", "image.png.tmp-"), 1234);
  EXPECT_EQ(temporaryOwner("image.png.tmp-", "image.png.tmp-"), -1);     // no PID
  EXPECT_EQ(temporaryOwner("image.png.tmp-12a", "image.png.tmp-"), -1);  // not digits
  EXPECT_EQ(temporaryOwner("mask.png.tmp-1234", "image.png.tmp-"), -1);  // another file's
  EXPECT_EQ(temporaryOwner("image.png.tmp-99999999999999999999", "image.png.tmp-"), -1);
}

TEST_F(OutputPath, ProcessRunningKnowsTheLivingFromTheDead) {
  EXPECT_TRUE(processRunning(long(::getpid())));
  EXPECT_FALSE(processRunning(deadPid()));
}

TEST_F(OutputPath, StaleTemporariesOfDeadProcessesAreRemovedOthersKept) {
  const std::string file = at("view.png");
  const std::string dead = std::to_string(deadPid()), alive = std::to_string(::getpid());
  write(file + ".tmp-" + dead);
  write(file + ".partial-" + dead);
  write(file + ".tmp-" + alive);          // a run that still writes it
  fs::create_directory(file + ".tmp-1");  // a folder of that name: not ours to remove
  write(at("other.png.tmp-") + dead);     // another file's temporary
  removeStaleTemporaryFiles(file);
  EXPECT_FALSE(fs::exists(file + ".tmp-" + dead));
  EXPECT_FALSE(fs::exists(file + ".partial-" + dead));
  EXPECT_TRUE(fs::exists(file + ".tmp-" + alive));
  EXPECT_TRUE(fs::is_directory(file + ".tmp-1"));
  EXPECT_TRUE(fs::exists(at("other.png.tmp-") + dead));
}

TEST_F(OutputPath, NearestExistingFolderWalksUpToWhatExists) {
  EXPECT_EQ(fs::path(nearestExistingFolder(at("a/b/c/out.png"))), dir_);
  fs::create_directories(dir_ / "a" / "b");
  EXPECT_EQ(fs::path(nearestExistingFolder(at("a/b/c/out.png"))), dir_ / "a" / "b");
  write(at("file"));
  EXPECT_NE(refusal([&] { nearestExistingFolder(at("file/out.png")); }), "");
}

TEST_F(OutputPath, SingleFileOutputsRefuseFoldersLinksAndSpecialFiles) {
  fs::create_directory(at("folder.png"));
  EXPECT_NE(refusal([&] { checkOutputFile(at("folder.png")); }), "");
  fs::create_directory_symlink(at("folder.png"), at("link.png"));
  EXPECT_NE(refusal([&] { checkOutputFile(at("link.png")); }), "");
  ASSERT_EQ(mkfifo(at("fifo.png").c_str(), 0600), 0);
  EXPECT_NE(refusal([&] { checkOutputFile(at("fifo.png")); }), "");
  // What the user named as a file is replaced; a new file in a new folder is fine.
  write(at("old.png"));
  EXPECT_EQ(refusal([&] { checkOutputFile(at("old.png")); }), "");
  EXPECT_EQ(refusal([&] { checkOutputFile(at("new/deeper/view.png")); }), "");
  // Nothing was created or removed by the checks.
  EXPECT_TRUE(fs::is_directory(at("folder.png")));
  EXPECT_TRUE(fs::exists(at("old.png")));
  EXPECT_FALSE(fs::exists(at("new")));
}

TEST_F(OutputPath, OutputFoldersMustBeFoldersThatCanBeWritten) {
  EXPECT_EQ(refusal([&] { checkOutputFolder(at("out")); }), "");
  write(at("file"));
  EXPECT_NE(refusal([&] { checkOutputFolder(at("file/out")); }), "");
  // A read-only folder is refused. Root's override of the permission bits would make it
  // writable, so as root the check runs in a child that has become nobody.
  fs::create_directory(at("readonly"));
  ::chmod(at("readonly").c_str(), 0555);
  const std::string inside = at("readonly/out");
  const pid_t child = fork();
  if (child == 0) {
    if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) _exit(3);
    _exit(refusal([&] { checkOutputFolder(inside); }).empty() ? 1 : 0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ::chmod(at("readonly").c_str(), 0755);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0)
      << "1: a read-only folder was accepted; 3: cannot become nobody";
}

}  // namespace
}  // namespace parallax
