// OutputSet: a set replaces only files parallax wrote, keeps the folder's mode, owner, group and
// ACL, refuses an unwritable folder before any work, and a killed commit is rolled forward.
#include "parallax/jobs/layer_output.h"

#include <fcntl.h>
#include <grp.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <sys/xattr.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/core/output_path.h"
#include "parallax/io/image_file.h"

namespace parallax::jobs {
namespace {

namespace fs = std::filesystem;

constexpr uid_t kNobody = 65534;
constexpr gid_t kNogroup = 65534;

// A fresh folder under /tmp that `nobody` may enter (for the tests that drop root).
class OutputSetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/parallax-output-set-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    root_ = pattern;
    ::chmod(root_.c_str(), 0755);
  }
  void TearDown() override {
    std::error_code ec;
    // A read-only folder of a test: writable again so that it can go.
    for (fs::recursive_directory_iterator it(root_, ec), end; !ec && it != end; it.increment(ec))
      if (it->is_directory(ec)) ::chmod(it->path().c_str(), 0755);
    fs::remove_all(root_, ec);
  }
  std::string at(const std::string& name) const { return (fs::path(root_) / name).string(); }
  std::string root_;
};

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The folder's entries, sorted ("name" or "name/" for a folder).
std::set<std::string> entries(const std::string& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder))
    names.insert(entry.path().filename().string() + (entry.is_directory() ? "/" : ""));
  return names;
}

// One set of `names`, each file holding "NAME of TAG", committed into `dir`.
void writeSet(const std::string& dir, const std::vector<std::string>& names,
              const std::string& tag) {
  OutputSet set(dir);
  for (const std::string& name : names) writeFileAtomically(set.path(name), name + " of " + tag);
  set.commit();
}

// The message of the InputError `run` throws ("" when it throws none).
std::string refusal(const std::function<void()>& run) {
  try {
    run();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Runs `body` in a child process, as `nobody` when this process is root: root's override of
// the permission bits would otherwise let it write a read-only folder, and such a test would
// prove nothing. Returns the child's exit code (body's result), -1 when it did not exit.
int inChildProcess(const std::function<int()>& body, bool unprivileged) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (unprivileged && geteuid() == 0) {
      if (setgroups(0, nullptr) != 0 || setgid(kNogroup) != 0 || setuid(kNobody) != 0) _exit(99);
    }
    _exit(body());
  }
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

TEST_F(OutputSetTest, ANewSetReplacesItsOwnFilesAndLeavesTheOthers) {
  const std::string dir = at("set");
  writeSet(dir, {"image.png", "mask.png", "render.json"}, "first");
  writeText(at("set/notes.txt"), "the user's notes");
  writeSet(dir, {"image.png", "mask.png", "render.json"}, "second");
  EXPECT_EQ(readText(at("set/image.png")), "image.png of second");
  EXPECT_EQ(readText(at("set/render.json")), "render.json of second");
  EXPECT_EQ(readText(at("set/notes.txt")), "the user's notes");
  // Nothing else: no temporary folder, and the list of ours (hidden).
  EXPECT_EQ(entries(dir), (std::set<std::string>{".parallax-outputs", "image.png", "mask.png",
                                                 "notes.txt", "render.json"}));
}

TEST_F(OutputSetTest, TheFolderKeepsItsModeOwnerGroupAndAcl) {
  const std::string dir = at("shared");
  ASSERT_TRUE(fs::create_directory(dir));
  // A shared group folder: setgid and group-writable, owned by another user and group (as root
  // the test can give it away; otherwise it stays ours, and the mode and ACL are still checked).
  const bool root = geteuid() == 0;
  if (root) {
    ASSERT_EQ(::chown(dir.c_str(), kNobody, 4 /* adm */), 0);
  }
  ASSERT_EQ(::chmod(dir.c_str(), 02775), 0);
  // An ACL granting `nobody` rwx (access) and the same as the default for new files: user::rwx
  // user:65534:rwx group::r-x mask::rwx other::r-x, in the kernel's xattr layout.
  const auto entry = [](uint16_t tag, uint16_t perm, uint32_t id) {
    std::string bytes(8, '\0');
    bytes[0] = char(tag & 0xff), bytes[1] = char(tag >> 8), bytes[2] = char(perm);
    for (int i = 0; i < 4; ++i) bytes[size_t(4 + i)] = char((id >> (8 * i)) & 0xff);
    return bytes;
  };
  const std::string acl = std::string("\x02\0\0\0", 4) + entry(0x01, 7, ~0u) +
                          entry(0x02, 7, kNobody) + entry(0x04, 5, ~0u) + entry(0x10, 7, ~0u) +
                          entry(0x20, 5, ~0u);
  const bool acls =
      ::setxattr(dir.c_str(), "system.posix_acl_access", acl.data(), acl.size(), 0) == 0 &&
      ::setxattr(dir.c_str(), "system.posix_acl_default", acl.data(), acl.size(), 0) == 0;
  struct stat before = {};
  ASSERT_EQ(::stat(dir.c_str(), &before), 0);
  const auto aclOf = [&](const char* name) {
    std::string bytes(256, '\0');
    const ssize_t n = ::getxattr(dir.c_str(), name, bytes.data(), bytes.size());
    bytes.resize(n < 0 ? 0 : size_t(n));
    return bytes;
  };
  const std::string accessBefore = aclOf("system.posix_acl_access");

  writeSet(dir, {"image.png", "render.json"}, "first");
  writeSet(dir, {"image.png", "render.json"}, "second");

  struct stat after = {};
  ASSERT_EQ(::stat(dir.c_str(), &after), 0);
  EXPECT_EQ(after.st_ino, before.st_ino) << "the folder itself was replaced";
  EXPECT_EQ(after.st_mode & 07777, 02775u);
  EXPECT_EQ(after.st_uid, before.st_uid);
  EXPECT_EQ(after.st_gid, before.st_gid);
  if (acls) {
    EXPECT_EQ(aclOf("system.posix_acl_access"), accessBefore);
    EXPECT_EQ(aclOf("system.posix_acl_default"), acl);
  }
  // The new files were made in the folder (setgid): they have its group, and its default ACL.
  struct stat file = {};
  ASSERT_EQ(::stat(at("shared/image.png").c_str(), &file), 0);
  EXPECT_EQ(file.st_gid, before.st_gid);
  if (acls) {
    std::string bytes(256, '\0');
    EXPECT_GT(::getxattr(at("shared/image.png").c_str(), "system.posix_acl_access", bytes.data(),
                         bytes.size()),
              0)
        << "the default ACL did not reach the new file";
  }
}

TEST_F(OutputSetTest, AUserFolderWithAnOutputNameIsRefusedAndKept) {
  const std::string dir = at("out");
  writeSet(dir, {"image.png", "render.json"}, "first");
  ASSERT_TRUE(fs::create_directory(at("out/mask.png")));
  writeText(at("out/mask.png/mine.txt"), "the user's file");
  const std::vector<std::string> names{"image.png", "mask.png", "render.json"};
  const std::string before = refusal([&] { OutputSet::check(dir, names); });
  EXPECT_NE(before.find("mask.png: is a folder (not written by parallax)"), std::string::npos)
      << before;
  EXPECT_NE(before.find("parallax replaces only files it wrote"), std::string::npos) << before;
  // commit() refuses it too (it was made after the check), before any file moves.
  const std::string atCommit = refusal([&] { writeSet(dir, names, "second"); });
  EXPECT_NE(atCommit.find("is a folder"), std::string::npos) << atCommit;
  EXPECT_EQ(readText(at("out/mask.png/mine.txt")), "the user's file");
  EXPECT_EQ(readText(at("out/image.png")), "image.png of first");
  EXPECT_EQ(entries(dir),
            (std::set<std::string>{".parallax-outputs", "image.png", "mask.png/", "render.json"}));
}

TEST_F(OutputSetTest, FilesLinksAndFifosNotOursAreRefused) {
  const std::string dir = at("out");
  ASSERT_TRUE(fs::create_directory(dir));
  writeText(at("out/image.png"), "the user's picture");
  EXPECT_NE(refusal([&] {
              OutputSet::check(dir, {"image.png"});
            }).find("image.png: is a file not written by parallax"),
            std::string::npos);
  EXPECT_NE(refusal([&] { writeSet(dir, {"image.png"}, "new"); }).find("not written by parallax"),
            std::string::npos);
  EXPECT_EQ(readText(at("out/image.png")), "the user's picture");
  fs::create_symlink("/etc/hostname", at("out/mask.png"));
  EXPECT_NE(refusal([&] { OutputSet::check(dir, {"mask.png"}); }).find("symbolic link"),
            std::string::npos);
  ASSERT_EQ(::mkfifo(at("out/render.json").c_str(), 0644), 0);
  EXPECT_NE(refusal([&] { OutputSet::check(dir, {"render.json"}); }).find("FIFO"),
            std::string::npos);
  // Names the set does not write are nobody's business.
  EXPECT_EQ(refusal([&] { OutputSet::check(dir, {"display.json"}); }), "");
}

TEST_F(OutputSetTest, AnEarlierVersionsRecordMakesItsFilesOurs) {
  // Before the list of ours existed: render.json (program parallax) lists its outputs.
  const std::string dir = at("old");
  ASSERT_TRUE(fs::create_directory(dir));
  writeText(at("old/render.json"),
            R"({"program": "parallax", "outputs": {"image": "image.png", "display": "display.json"},
                "frames": [{"image": "image-1.png", "mask": "mask-1.png"}]})");
  for (const char* name : {"image.png", "display.json", "image-1.png", "mask-1.png"})
    writeText(at(std::string("old/") + name), "old");
  writeText(at("old/mask.png"), "not listed");
  EXPECT_EQ(refusal([&] {
              OutputSet::check(dir, {"image.png", "display.json", "image-1.png", "render.json"});
            }),
            "");
  EXPECT_NE(refusal([&] { OutputSet::check(dir, {"mask.png"}); }).find("not written by parallax"),
            std::string::npos);
  // Another program's render.json lists nothing of ours, nor does a name with a path.
  writeText(at("old/render.json"), R"({"program": "other", "outputs": {"image": "image.png"}})");
  EXPECT_NE(refusal([&] { OutputSet::check(dir, {"image.png"}); }), "");
}

TEST_F(OutputSetTest, FilesOfAnEarlierSetThatTheNewOneLacksAreRemoved) {
  const std::string dir = at("nmf");
  writeSet(dir, {"image-1.png", "mask-1.png", "image-2.png", "mask-2.png", "render.json"},
           "rank 2");
  writeText(at("nmf/notes.txt"), "mine");
  writeSet(dir, {"image.png", "mask.png", "render.json"}, "rank 1");
  EXPECT_EQ(entries(dir), (std::set<std::string>{".parallax-outputs", "image.png", "mask.png",
                                                 "notes.txt", "render.json"}));
}

TEST_F(OutputSetTest, AReadOnlyFolderIsRefusedBeforeAnyWorkAndLeftAsItWas) {
  const std::string dir = at("readonly");
  writeSet(dir, {"image.png", "render.json"}, "first");
  ASSERT_EQ(::chmod(dir.c_str(), 0555), 0);
  const std::set<std::string> before = entries(dir);
  // As `nobody` (the folder is root's or ours, 0555): 1 = refused by check(), 2 = by the
  // constructor as well, naming the folder.
  const int code = inChildProcess(
      [&] {
        int refused = 0;
        if (refusal([&] {
              OutputSet::check(dir, {"image.png", "render.json"});
            }).find("cannot be written") != std::string::npos)
          ++refused;
        if (refusal([&] { OutputSet set(dir); }).find("cannot be written") != std::string::npos)
          ++refused;
        // A folder still to be made inside it: its nearest existing ancestor decides.
        if (refusal([&] {
              OutputSet::check(dir + "/new/deeper", {"image.png"});
            }).find("readonly: cannot be written") != std::string::npos)
          ++refused;
        return refused;
      },
      true);
  EXPECT_EQ(code, 3);
  EXPECT_EQ(entries(dir), before);
  EXPECT_EQ(readText(at("readonly/image.png")), "image.png of first");
  // The same folder, writable to this user, is written: the check is not a refusal of all.
  ASSERT_EQ(::chmod(dir.c_str(), 0777), 0);
  EXPECT_EQ(
      inChildProcess(
          [&] { return refusal([&] { OutputSet::check(dir, {"notes.txt"}); }).empty() ? 0 : 1; },
          true),
      0);
}

// A kill between two renames of a commit: the next set for the folder finishes the renames
// (roll forward), so that the record is never left without its files.
TEST_F(OutputSetTest, AKilledCommitIsRolledForward) {
  const std::string dir = at("killed");
  writeSet(dir, {"image.png", "mask.png", "render.json"}, "old");
  const int code = inChildProcess(
      [&] {
        OutputSet::setCommitHookForTests([](size_t renamed) {
          if (renamed == 1) _exit(7);  // killed after image.png moved in
        });
        writeSet(dir, {"image.png", "mask.png", "render.json"}, "new");
        return 0;
      },
      false);
  ASSERT_EQ(code, 7);
  EXPECT_EQ(readText(at("killed/image.png")), "image.png of new");
  EXPECT_EQ(readText(at("killed/render.json")), "render.json of old");  // not yet
  int temporaries = 0;
  for (const std::string& name : entries(dir)) temporaries += name.rfind(".parallax-tmp-", 0) == 0;
  EXPECT_EQ(temporaries, 1);

  {
    // Recovers; then dropped without a commit.
    OutputSet next(dir);
  }
  EXPECT_EQ(readText(at("killed/mask.png")), "mask.png of new");
  EXPECT_EQ(readText(at("killed/render.json")), "render.json of new");
  EXPECT_EQ(entries(dir),
            (std::set<std::string>{".parallax-outputs", "image.png", "mask.png", "render.json"}));
}

TEST_F(OutputSetTest, AKilledRunBeforeItsCommitLeavesTheOldSet) {
  const std::string dir = at("early");
  writeSet(dir, {"image.png", "render.json"}, "old");
  ASSERT_EQ(inChildProcess(
                [&] {
                  OutputSet set(dir);
                  writeFileAtomically(set.path("image.png"), "half");
                  _exit(9);  // killed before commit
                  return 0;
                },
                false),
            9);
  EXPECT_EQ(entries(dir).size(), 4u);  // the set, its list and the dead run's folder
  {
    // Opening a set recovers from the dead run.
    OutputSet next(dir);
  }
  EXPECT_EQ(entries(dir), (std::set<std::string>{".parallax-outputs", "image.png", "render.json"}));
  EXPECT_EQ(readText(at("early/image.png")), "image.png of old");
}

// An earlier version killed between moving the old folder aside (.NAME.old-PID) and the new one
// in: the old folder is the only copy of the user's files, and comes back.
TEST_F(OutputSetTest, AnEarlierVersionsFolderMovedAsideIsMovedBack) {
  ASSERT_TRUE(fs::create_directories(at(".set.old-999999999/mine")));
  writeText(at(".set.old-999999999/mine/notes.txt"), "the user's");
  ASSERT_TRUE(fs::create_directory(at(".set.tmp-999999999")));  // the new set, not moved in
  writeSet(at("set"), {"image.png"}, "new");
  EXPECT_EQ(readText(at("set/mine/notes.txt")), "the user's");
  EXPECT_EQ(readText(at("set/image.png")), "image.png of new");
  EXPECT_EQ(entries(root_), std::set<std::string>{"set/"});
  // With the folder there (the earlier commit finished), the leftovers just go.
  ASSERT_TRUE(fs::create_directory(at(".set.old-999999999")));
  writeSet(at("set"), {"image.png"}, "again");
  EXPECT_EQ(entries(root_), std::set<std::string>{"set/"});
  EXPECT_EQ(readText(at("set/mine/notes.txt")), "the user's");
}

TEST_F(OutputSetTest, StaleTemporaryFilesOfKilledRunsAreRemoved) {
  const std::string file = at("view.png");
  writeText(file + ".partial-999999999", "a killed video");
  writeText(file + ".tmp-999999999", "a killed picture");
  ASSERT_TRUE(fs::create_directory(file + ".partial-999999998"));  // a folder: not ours
  writeText(at("other.png.partial-999999999"), "another file's");
  const std::string live = file + ".partial-" + std::to_string(getppid());  // a running process
  writeText(live, "running");
  writeFileAtomically(file, "new");
  EXPECT_EQ(entries(root_), (std::set<std::string>{"other.png.partial-999999999", "view.png",
                                                   "view.png.partial-999999998/",
                                                   fs::path(live).filename().string()}));
}

TEST_F(OutputSetTest, SingleFileOutputsAreCheckedBeforeWork) {
  ASSERT_TRUE(fs::create_directory(at("folder.png")));
  EXPECT_NE(refusal([&] { checkOutputFile(at("folder.png")); }).find("is a folder"),
            std::string::npos);
  ASSERT_EQ(::mkfifo(at("fifo.png").c_str(), 0644), 0);
  EXPECT_NE(refusal([&] { checkOutputFile(at("fifo.png")); }).find("not a regular file"),
            std::string::npos);
  writeText(at("plain"), "a file");
  EXPECT_NE(refusal([&] { checkOutputFile(at("plain/x.png")); }).find("is a file"),
            std::string::npos);
  EXPECT_EQ(refusal([&] { checkOutputFile(at("new/deeper/x.png")); }), "");
  ASSERT_TRUE(fs::create_directory(at("ro")));
  ASSERT_EQ(::chmod(at("ro").c_str(), 0555), 0);
  EXPECT_EQ(inChildProcess(
                [&] {
                  return refusal([&] {
                           checkOutputFile(at("ro/x.mp4"));
                         }).find("cannot be written (Permission denied)") != std::string::npos
                             ? 0
                             : 1;
                },
                true),
            0);
}

}  // namespace
}  // namespace parallax::jobs
