#include "parallax/core/output_path.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include "parallax/core/error.h"

namespace parallax {

namespace fs = std::filesystem;

bool processRunning(long pid) {
  if (pid <= 0) return false;
  return ::kill(pid_t(pid), 0) == 0 || errno == EPERM;
}

long temporaryOwner(const std::string& name, const std::string& prefix) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return -1;
  const std::string pid = name.substr(prefix.size());
  if (pid.size() > 9 || pid.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stol(pid);
}

void removeStaleTemporaryFiles(const std::string& path) {
  const fs::path target(path);
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const std::string name = target.filename().string();
  if (name.empty()) return;
  std::vector<fs::path> stale;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    for (const char* kind : {".tmp-", ".partial-"}) {
      const long pid = temporaryOwner(entry, name + kind);
      // Only regular files: a folder of that name is not a temporary file of ours.
      if (pid > 0 && pid != long(::getpid()) && !processRunning(pid) &&
          it->symlink_status(ec).type() == fs::file_type::regular)
        stale.push_back(it->path());
    }
  }
  for (const fs::path& file : stale) fs::remove(file, ec);
}

std::string nearestExistingFolder(const std::string& path) {
  fs::path at = fs::absolute(fs::path(path.empty() ? "." : path)).lexically_normal();
  if (!at.has_filename()) at = at.parent_path();
  std::error_code ec;
  for (;;) {
    const fs::file_status status = fs::status(at, ec);
    if (fs::exists(status)) {
      if (!fs::is_directory(status))
        throw InputError(at.string(), "", "is a file, where " + path + " needs a folder");
      return at.string();
    }
    if (at == at.root_path() || !at.has_parent_path()) return at.string();
    at = at.parent_path();
  }
}

void checkWritableFolder(const std::string& folder, const std::string& advice) {
  // AT_EACCESS: the effective ids, those open() and mkdir() are checked with.
  if (::faccessat(AT_FDCWD, folder.c_str(), W_OK | X_OK, AT_EACCESS) != 0)
    throw InputError(folder, "",
                     std::string("cannot be written (") + std::strerror(errno) + "): " + advice +
                         "; nothing was done");
}

void checkOutputFile(const std::string& path) {
  struct stat info;
  if (::stat(path.c_str(), &info) == 0) {
    if (S_ISDIR(info.st_mode))
      throw InputError(path, "", "is a folder; the output is a file: give a file name");
    if (!S_ISREG(info.st_mode))
      throw InputError(path, "",
                       "is not a regular file (a FIFO, device or socket); parallax writes only "
                       "files: give another file name");
  }
  checkWritableFolder(nearestExistingFolder(fs::path(path).parent_path().string()),
                      "choose another place for " + path);
}

void checkOutputFolder(const std::string& dir) {
  checkWritableFolder(nearestExistingFolder(dir), "choose another {output}");
}

}  // namespace parallax
