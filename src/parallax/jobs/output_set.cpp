// OutputSet (output_set.h): written into a temporary folder, committed file by file, rolled
// forward after a kill.
#include "parallax/jobs/output_set.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "parallax/jobs/output_set.h"

#include <sys/file.h>
#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <set>

#include "parallax/core/error.h"
#include "parallax/core/output_path.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_reader.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/reporter.h"
#include "parallax/jobs/requests.h"

namespace parallax::jobs {

namespace {

namespace fs = std::filesystem;

// ".NAME" KIND SUFFIX: the temporary (".tmp-") and old (".old-") folders that versions before
// the files were committed one by one put beside NAME.
std::string sibling(const std::string& name, const char* kind, const std::string& suffix) {
  std::string text(".");
  text.append(name).append(kind).append(suffix);
  return text;
}

// The earlier versions' .NAME.tmp-PID and .NAME.old-PID folders beside `target` whose process
// is gone. A .tmp- folder held the new set and links to the folder's files (or, after the
// exchange, the old folder, whose files the new one links): removed. An .old- folder is the old
// folder moved aside before the new one moved in: when `target` is missing, the run was killed
// between the two renames and it is the only copy, so it is moved back; otherwise removed.
void recoverLegacyTemporaries(const fs::path& target) {
  const std::string name = target.filename().string();
  std::vector<fs::path> stale;
  std::error_code ec;
  for (fs::directory_iterator it(target.parent_path(), ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    for (const char* kind : {".tmp-", ".old-"}) {
      const long pid = temporaryOwner(entry, sibling(name, kind, ""));
      if (pid <= 0 || processRunning(pid)) continue;
      if (kind[1] == 'o' && !fs::exists(fs::symlink_status(target, ec)))
        fs::rename(it->path(), target, ec);  // restored
      else
        stale.push_back(it->path());
    }
  }
  for (const fs::path& path : stale) fs::remove_all(path, ec);
}

constexpr const char* kTemporaryPrefix = ".parallax-tmp-";
constexpr const char* kManifest = ".parallax-outputs";  // the names of ours in DIR
constexpr const char* kMarker = ".parallax-commit";     // in a temporary folder: commit started

void (*commitHook)(size_t) = nullptr;

// A name an output set may have: one file name in DIR, not one of the set's own.
bool plainName(const std::string& name) {
  return !name.empty() && name != "." && name != ".." &&
         std::find(name.begin(), name.end(), '/') == name.end() && !name.starts_with(".parallax-");
}

// The strings of `value` (an array of strings, or an object of them) that are plain names.
void addNames(const JsonReader& value, std::set<std::string>& names) {
  if (value.isString()) {
    if (plainName(value.string())) names.insert(value.string());
    return;
  }
  if (value.isArray())
    for (const JsonReader& element : value.elements()) addNames(element, names);
  else if (value.isObject())
    for (const auto& member : value.members()) addNames(member.second, names);
}

// The names of DIR that parallax wrote: the list commit() keeps, and what a record of an earlier
// version lists (render.json's /outputs and /frames; a calibration index's patterns). A file
// that does not parse lists nothing.
std::set<std::string> ownedNames(const fs::path& folder) {
  std::set<std::string> names;
  const auto read = [&](const char* file, const std::function<void(const JsonReader&)>& take) {
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(folder / file, ec))) return;
    try {
      const JsonDocument document = JsonDocument::parseFile((folder / file).string());
      const JsonReader root = document.root();
      if (root.isObject()) take(root);
    } catch (const InputError&) {
    }
  };
  read(kManifest, [&](const JsonReader& root) {
    if (root.string("program", "") != "parallax") return;
    if (const auto files = root.find("files")) addNames(*files, names);
  });
  read("render.json", [&](const JsonReader& root) {
    if (root.string("program", "") != "parallax") return;
    names.insert("render.json");
    if (const auto outputs = root.find("outputs")) addNames(*outputs, names);
    if (const auto frames = root.find("frames")) addNames(*frames, names);
  });
  read("index.json", [&](const JsonReader& root) {
    const auto patterns = root.find("patterns");
    if (!patterns || !patterns->isArray() || !root.has("layer_order")) return;
    names.insert({"index.json", "README.txt"});
    for (const JsonReader& pattern : patterns->elements())
      if (const auto file = pattern.find("file")) addNames(*file, names);
  });
  return names;
}

// Why `name` in `folder` cannot be replaced ("" when it can: absent, or a file of ours).
std::string conflict(const fs::path& folder, const std::string& name,
                     const std::set<std::string>& owned) {
  struct stat info;
  if (::lstat((folder / name).c_str(), &info) != 0) return "";
  if (S_ISREG(info.st_mode)) return owned.count(name) ? "" : "is a file not written by parallax";
  if (S_ISDIR(info.st_mode)) return "is a folder (not written by parallax)";
  if (S_ISLNK(info.st_mode)) return "is a symbolic link (not written by parallax)";
  return "is a FIFO, device or socket";
}

void refuseConflicts(const std::string& dir, const fs::path& folder,
                     const std::vector<std::string>& names) {
  const std::set<std::string> owned = ownedNames(folder);
  for (const std::string& name : names) {
    const std::string why = conflict(folder, name, owned);
    if (!why.empty())
      throw InputError((fs::path(dir) / name).string(), "",
                       why +
                           "; parallax replaces only files it wrote: move it or choose another "
                           "{output}");
  }
}

// An exclusive lock on the folder while a set is committed or a killed run's set recovered.
class FolderLock {
 public:
  explicit FolderLock(const fs::path& folder)
      : fd_(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ >= 0)
      while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
      }
  }
  ~FolderLock() {
    if (fd_ >= 0) ::close(fd_);
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_;
};

void writeManifest(const fs::path& folder, const fs::path& temporary,
                   const std::vector<std::string>& files) {
  JsonWriter manifest;
  manifest.set("/program", "parallax");
  manifest.set("/about", "the files parallax wrote here, which the next output set may replace");
  manifest.set("/files", files);
  const fs::path next = temporary / (std::string(kManifest) + ".next");
  writeFileAtomically(next.string(), manifest.dump() + "\n");
  fs::rename(next, folder / kManifest);
}

std::vector<std::string> stringList(const JsonReader& root, const char* key) {
  std::vector<std::string> list;
  if (const auto value = root.find(key))
    for (const JsonReader& element : value->elements())
      if (plainName(element.string())) list.push_back(element.string());
  return list;
}

// The renames of a commit whose marker is written (by this process, or by a killed one whose
// commit is rolled forward): the list of ours first grows to cover old and new files, then each
// file moves in, then files of ours that the new set lacks go, then the list is the new set's.
void finishCommit(const fs::path& folder, const fs::path& temporary) {
  const JsonDocument marker = JsonDocument::parseFile((temporary / kMarker).string());
  const std::vector<std::string> files = stringList(marker.root(), "files");
  const std::vector<std::string> remove = stringList(marker.root(), "remove");
  std::set<std::string> all = ownedNames(folder);
  all.insert(files.begin(), files.end());
  writeManifest(folder, temporary, {all.begin(), all.end()});
  std::error_code ec;
  for (size_t i = 0; i < files.size(); ++i) {
    const fs::path from = temporary / files[i];
    if (!fs::exists(fs::symlink_status(from, ec))) continue;  // moved before a kill
    // rename() of a file never removes a folder (EISDIR): a folder made since the check stays.
    if (::rename(from.c_str(), (folder / files[i]).c_str()) != 0)
      throw InputError((folder / files[i]).string(), "",
                       std::string("cannot move the new file into place: ") + std::strerror(errno));
    if (commitHook) commitHook(i + 1);
  }
  for (const std::string& name : remove) {
    if (std::find(files.begin(), files.end(), name) != files.end()) continue;
    if (fs::is_regular_file(fs::symlink_status(folder / name, ec))) fs::remove(folder / name, ec);
  }
  writeManifest(folder, temporary, files);
  fs::remove_all(temporary, ec);
}

// Temporary folders of processes that no longer run: committed ones finished, others removed.
void recoverKilledSets(const fs::path& folder) {
  std::vector<fs::path> stale;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const long pid = temporaryOwner(it->path().filename().string(), kTemporaryPrefix);
    if (pid > 0 && pid != long(::getpid()) && !processRunning(pid) &&
        it->symlink_status(ec).type() == fs::file_type::directory)
      stale.push_back(it->path());
  }
  for (const fs::path& temporary : stale) {
    if (fs::is_regular_file(temporary / kMarker, ec)) {
      try {
        finishCommit(folder, temporary);
      } catch (const std::exception&) {
        // Left as it is: the files stay in the temporary folder rather than being lost.
      }
    } else {
      fs::remove_all(temporary, ec);
    }
  }
}

}  // namespace

void OutputSet::check(const std::string& dir, const std::vector<std::string>& names) {
  const std::string shown = dir.empty() ? "." : dir;
  std::error_code ec;
  const fs::file_status status = fs::status(shown, ec);
  if (fs::exists(status) && !fs::is_directory(status))
    throw InputError(shown, "", "is a file; the output must be a folder");
  checkOutputFolder(shown);
  if (fs::exists(status)) refuseConflicts(shown, shown, names);
}

void OutputSet::setCommitHookForTests(void (*hook)(size_t)) {
  commitHook = hook;
}

OutputSet::OutputSet(const std::string& dir) : dir_(dir.empty() ? "." : dir) {
  fs::path target = fs::absolute(dir_).lexically_normal();
  if (!target.has_filename()) target = target.parent_path();
  folder_ = target.string();
  std::error_code ec;
  if (fs::exists(fs::status(target, ec)) && !fs::is_directory(fs::status(target, ec)))
    throw InputError(dir_, "", "is a file; the output must be a folder");
  checkOutputFolder(dir_);
  try {
    if (target.has_parent_path() && target != target.root_path() &&
        fs::is_directory(target.parent_path(), ec))
      recoverLegacyTemporaries(target);
    fs::create_directories(target);
    {
      const FolderLock lock(target);
      recoverKilledSets(target);
    }
    temporary_ = (target / (kTemporaryPrefix + std::to_string(::getpid()))).string();
    fs::remove_all(temporary_);
    fs::create_directory(temporary_);
  } catch (const fs::filesystem_error& e) {
    throw InputError(dir_, "",
                     std::string("cannot create the output folder: ") + e.code().message());
  }
}

OutputSet::~OutputSet() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(temporary_, ec);
}

std::string OutputSet::path(const std::string& name) {
  if (!plainName(name)) throw std::invalid_argument("OutputSet::path: not a file name: " + name);
  if (std::find(names_.begin(), names_.end(), name) == names_.end()) names_.push_back(name);
  return (fs::path(temporary_) / name).string();
}

void OutputSet::commit() {
  if (committed_) return;
  const fs::path folder(folder_), temporary(temporary_);
  const FolderLock lock(folder);
  refuseConflicts(dir_, folder, names_);
  // Ours, and not in the new set: what the new record no longer describes.
  std::vector<std::string> remove;
  std::error_code ec;
  for (const std::string& name : ownedNames(folder))
    if (std::find(names_.begin(), names_.end(), name) == names_.end() &&
        fs::is_regular_file(fs::symlink_status(folder / name, ec)))
      remove.push_back(name);
  JsonWriter marker;
  marker.set("/files", names_);
  marker.set("/remove", remove);
  writeFileAtomically((temporary / kMarker).string(), marker.dump() + "\n");
  // From here on the temporary folder is kept if a rename fails: the next run into DIR finishes
  // the commit (or leaves the files there), rather than the files being lost.
  committed_ = true;
  try {
    finishCommit(folder, temporary);
  } catch (const fs::filesystem_error& e) {
    throw InputError(dir_, "",
                     std::string("cannot commit the output files: ") + e.code().message());
  }
}

}  // namespace parallax::jobs
