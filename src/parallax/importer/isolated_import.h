// Private to the importer: running a third-party importer in a child process
// (isolated_import.cpp, docs/import.md "Isolation"). The child reads the file, converts it to
// FileContents and writes them to a memfd in our own flat layout; the parent reads them back
// with bounds-checked parsing. A crash, abort, hang or runaway allocation in the child becomes
// an InputError naming the file; the parent process is never at risk.
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "parallax/importer/mesh_reading.h"

namespace parallax::meshio {

// Runs `read(path)` in a forked child under importerLimits() and returns its FileContents.
// `importer` names the importer in messages ("the FBX importer (assimp)"). An InputError the
// child throws is rethrown with its message.
FileContents readIsolated(const std::string& path, const std::string& importer,
                          const std::function<FileContents(const std::string&)>& read);

// readAssimp without the child process: the conversion itself (mesh_assimp.cpp), for the
// child and for the tests and the measurement that compare both paths.
FileContents readAssimpInProcess(const std::string& path);

// The flat layout (native byte order: the writer and the reader are one program on one
// machine). serializeContents is what the child writes; parseContents throws InputError for
// `path` on anything that does not parse exactly (a count beyond the bytes present, a
// truncated or garbled blob, trailing bytes). A blob may also carry a refusal: parseContents
// then throws it as the InputError it was.
std::string serializeContents(const FileContents& contents);
std::string serializeRefusal(const std::string& message);
FileContents parseContents(std::string_view blob, const std::string& path,
                           const std::string& importer);

// Test-only: when set, the child calls it before reading the file (to make it abort, crash,
// allocate without bound, spin or sleep). Never set outside tests.
extern void (*childFaultForTests)();

}  // namespace parallax::meshio
