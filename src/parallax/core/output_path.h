// Where outputs may be written, checked before any work, and the temporaries of killed runs.
// The rules (docs/inputs.md, "Outputs"): parallax replaces only files it wrote, never a folder,
// a link or a special file; an output whose folder cannot be written is refused before the work
// that would fill it.
#pragma once

#include <string>

namespace parallax {

// Whether process `pid` still runs (a process of another user counts).
bool processRunning(long pid);

// The PID in NAME + PREFIX + PID (PREFIX included in `prefix`), or -1 when `name` is not of that
// form.
long temporaryOwner(const std::string& name, const std::string& prefix);

// Removes PATH.tmp-PID and PATH.partial-PID files left by processes that no longer run (a killed
// run's half-written FILE). Folders of those names are left alone.
void removeStaleTemporaryFiles(const std::string& path);

// The folder that holds (or would hold) `path`, else its nearest existing ancestor: where the
// first file or folder of the output is created. Throws InputError naming `path` when that
// ancestor is a file.
std::string nearestExistingFolder(const std::string& path);

// Refuses (InputError naming `folder`, then `advice`) a folder this process cannot create files
// in: access()'s answer for the effective ids, so that it agrees with what open() and mkdir()
// will do (root's override of the permission bits included; a read-only mount is refused).
void checkWritableFolder(const std::string& folder, const std::string& advice);

// Before any work for a single-file output PATH (view -o, simulate -o, --video FILE): refuses a
// PATH that is a folder, a link to one or a special file (a FIFO, a device, a socket) and a PATH
// whose folder (or nearest existing ancestor) cannot be written. A regular file is replaced: the
// user named it.
void checkOutputFile(const std::string& path);

// Before any work for an output folder DIR: DIR (or its nearest existing ancestor) must be a
// folder this process can write.
void checkOutputFolder(const std::string& dir);

}  // namespace parallax
