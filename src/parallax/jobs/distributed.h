// One frame split across the job's processes (docs/distributed.md): each renders its bands of
// rows, rank 0 merges them and writes the outputs. Alone (no mpirun) both are no-ops.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <vector>

#include "parallax/image/image.h"
#include "parallax/jobs/reporter.h"
#include "parallax/render/render_settings.h"

namespace parallax::jobs {

// This process's share of one frame: its bands of rows (RenderSettings::bandParts).
RenderSettings frameShare(RenderSettings settings);

// After every process rendered its share: the images' (or 8-bit codes') bits merged onto rank
// 0, the ray counts summed and the slowest share's seconds taken. Returns whether this process
// writes the outputs (rank 0); the others stop there.
bool mergeFrameShares(std::initializer_list<Image*> images, RenderStats& stats, Reporter& reporter);
bool mergeFrameShares(std::vector<uint8_t>& codes, RenderStats& stats, Reporter& reporter);

// Whether this process is the one that writes outputs made once for the whole job (rank 0).
bool writesJobOutputs();

}  // namespace parallax::jobs
