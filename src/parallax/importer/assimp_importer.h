// assimp, the third-party importer behind the formats our own readers do not read
// (docs/import.md): the release this build runs, and the limits of the child process it runs in
// (importer/isolated_import.cpp).
#pragma once

namespace parallax {

// The assimp library this build runs, as {major, minor, patch} (`parallax --version` names
// it): which files crash it is a property of its release (tests read it).
struct LibraryVersion {
  int major = 0, minor = 0, patch = 0;
};
LibraryVersion assimpVersion();

// The limits of the child process that third-party importers (assimp) run in
// (docs/import.md, "Isolation"): its memory budget (address space on top of what the process
// had when it forked) and CPU time; past twice the CPU time plus 5 s of wall-clock time, a
// child that has used no CPU for a second (a hang) is ended too. 0: the default (memory: 3/4 of
// physical memory, as
// --max-memory's default; CPU: kDefaultImporterCpuSeconds). Process-wide; jobs sets them from
// the request limits (--max-memory, --max-time, Python's set_limits) before it loads a scene.
inline constexpr double kDefaultImporterCpuSeconds = 300;
struct ImporterLimits {
  double memoryBytes = 0;
  double cpuSeconds = 0;
};
void setImporterLimits(const ImporterLimits& limits);
// With the defaults filled in.
ImporterLimits importerLimits();

}  // namespace parallax
