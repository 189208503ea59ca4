// factorizeLayers: both layers of T time-multiplexed frames by weighted non-negative
// multiplicative updates (layer_problem.h, the problem; docs/content-adaptive.md).
#pragma once

#include <vector>

#include "parallax/layers/layer_problem.h"

namespace parallax {

// factorizeLayers' over-relaxed multiplicative updates (docs/content-adaptive.md): with
// m = x num / den the plain update,
//     x <- clamp(max(x + kNmfOverRelaxation (m - x), min(m, kNmfShrinkFloor x)), 0, 1),
// a step 1.9 times as long as the plain one's along the same line, which still never increases
// E (the updates' quadratic bound is symmetric about m).
inline constexpr float kNmfOverRelaxation = 1.9f, kNmfShrinkFloor = 0.1f;
// That update of one value x whose plain multiplicative update is `multiplicative` (before the
// clamp to [0, 1]).
float overRelaxedUpdate(float x, float multiplicative);

// Both layers of every frame, starting from `frames` (clamped to [0, 1]).
std::vector<LayerFrame> factorizeLayers(const std::vector<TrainingView>& views,
                                        std::vector<LayerFrame> frames, int iterations,
                                        int threads = 0, SolveReport* report = nullptr,
                                        const SolveProgress& progress = {},
                                        const RearDiffuser& diffuser = {});

}  // namespace parallax
