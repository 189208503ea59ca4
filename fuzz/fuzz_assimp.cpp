// The assimp route through its child process (importer/isolated_import.cpp): the input is written
// as a file of the format its first bytes announce (FBX, DirectX .x, Collada, OFF, 3DS, ...; else
// one of the formats only assimp reads, picked by the first byte; assimp itself then also tries
// the others by their signatures) and read by loadMeshFile, which runs assimp in a child. A
// crash, abort, hang or runaway allocation of the child is a clean refusal (InputError), not a
// finding: only this process failing is. The child's limits are kept below libFuzzer's
// (-timeout=10, -rss_limit_mb) so that they, not libFuzzer, stop a runaway child.
//
// An input beginning with the answer's magic "PPLXIMP1" is parsed as a child's answer
// (parseContents) in this process instead: that parser is what a compromised child would
// attack, and libFuzzer's coverage sees it (the child's coverage stays in the child).
#include <array>
#include <string>

#include "fuzz_mesh_support.h"
#include "parallax/importer/assimp_importer.h"
#include "parallax/importer/isolated_import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace parallax;
  using namespace parallax::fuzz;
  static const bool limited = [] {
    setImporterLimits({1024.0 * 1024.0 * 1024.0, 1.5});  // wall clock: 2 x 1.5 + 5 = 8 s
    return true;
  }();
  (void)limited;
  const std::string_view bytes = asText(data, size);
  if (bytes.starts_with("PPLXIMP1"))
    return refuseCleanly([&] { meshio::parseContents(bytes, "answer", "the fuzz importer"); });

  const auto starts = [&](std::string_view magic) { return bytes.starts_with(magic); };
  const auto has = [&](std::string_view text) {
    return bytes.substr(0, 1024).find(text) != std::string_view::npos;
  };
  std::string extension;
  if (starts("Kaydara FBX Binary") || has("; FBX ") || has("FBXHeaderExtension"))
    extension = "fbx";
  else if (starts("xof "))
    extension = "x";
  else if (has("<COLLADA"))
    extension = "dae";
  else if (starts("OFF") || starts("COFF") || starts("NOFF"))
    extension = "off";
  else if (size >= 2 && data[0] == 0x4d && data[1] == 0x4d)
    extension = "3ds";
  else if (starts("AC3D"))
    extension = "ac";
  else if (starts("*3DSMAX_ASCIIEXPORT"))
    extension = "ase";
  else if (starts("BLENDER"))
    extension = "blend";
  else if (starts("MS3D000000"))
    extension = "ms3d";
  else {
    static const std::array<const char*, 8> others = {"fbx", "x",  "dae", "off",
                                                      "3ds", "ac", "ase", "lwo"};
    extension = others[size ? data[0] % others.size() : 0];
  }
  return loadMesh(writeScratch("fuzz." + extension, bytes));
}
