// Gaussian splats in a PLY file, as 3DGS writes them (docs/splats.md, "Files"), internal to the
// importer: a vertex element with x y z, f_dc_0..2, f_rest_0..3K-1 (K = 0, 3, 8 or 15: degree 0
// to 3, channel-major), opacity (a logit), scale_0..2 (logs) and rot_0..3 (a quaternion w x y z),
// in any order and beside other properties (normals), read by name. The reader is the importer's
// own (loadMeshFile calls it); the writer serves the splat tools (jobs/splat_making.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "parallax/importer/ply_format.h"
#include "parallax/scene/gaussians.h"

namespace parallax::meshio {

// Whether the header's vertex element is splats: it has opacity, scale_0 and rot_0.
bool holdsSplats(const Header& header);

// The splats, their encodings undone (exp of the logs, the sigmoid of the logit, the
// coefficients coefficient-major). Throws InputError naming `path`, the Gaussian and the field:
// a property missing, f_rest's count not a degree's, a value not finite, a log scale outside
// [-30, 30] (no Gaussian is 10^13 times its neighbours), a zero quaternion, a count the file
// cannot hold.
GaussianCloud readSplats(const std::string& path, const std::string& bytes, const Header& header);

// The same from a file, without holding its bytes: a binary splat file (no list properties) is
// read after its header in blocks of whole records, each decoded on every core, so that the
// peak is the cloud and one block (docs/splats.md, "Memory"); the same cloud and the same
// refusals as readSplats. nullopt for any other file (a mesh, ASCII, lists, a header longer than
// 4 MiB): the caller reads it whole.
std::optional<GaussianCloud> readSplatsInBlocks(const std::string& path,
                                                std::vector<std::string>& warnings);

// The cloud as 3DGS writes it: binary little-endian floats x y z nx ny nz (zero) f_dc_0..2
// f_rest_* (channel-major) opacity (the logit) scale_0..2 (logs) rot_0..3 (w x y z), the file
// readSplats reads back to the same values (to float rounding of the logs and the logit).
std::string splatPlyBytes(const GaussianCloud& cloud);

}  // namespace parallax::meshio
