#include "parallax/jobs/distributed.h"

#include <chrono>
#include <cstdio>
#include <span>

#include "parallax/cluster/process_group.h"

namespace parallax::jobs {

RenderSettings frameShare(RenderSettings settings) {
  const cluster::ProcessGroup& group = cluster::world();
  settings.bandParts = group.size();
  settings.bandPart = group.rank();
  return settings;
}

namespace {

void mergeStats(cluster::ProcessGroup& group, RenderStats& stats) {
  uint64_t counts[] = {stats.cameraRays, stats.shadowRays, stats.secondaryRays, stats.bounceRays,
                       stats.cameraMisses};
  group.sumOnAll(counts);
  stats.cameraRays = counts[0];
  stats.shadowRays = counts[1];
  stats.secondaryRays = counts[2];
  stats.bounceRays = counts[3];
  stats.cameraMisses = counts[4];
  stats.seconds = group.maxOnAll(stats.seconds);
}

// The merge's time and size on rank 0: the serial part a split frame adds
// (docs/distributed.md, "Speed-up").
void reportMerge(const cluster::ProcessGroup& group, double bytes,
                 std::chrono::steady_clock::time_point start, Reporter& reporter) {
  if (!group.isRoot()) return;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  reporter.result(
      printed("merged %d ranks' shares (%.1f MB) in %.3f s", group.size(), bytes / 1e6, seconds));
}

}  // namespace

bool mergeFrameShares(std::initializer_list<Image*> images, RenderStats& stats,
                      Reporter& reporter) {
  cluster::ProcessGroup& group = cluster::world();
  if (group.size() == 1) return true;
  const auto start = std::chrono::steady_clock::now();
  double bytes = 0;
  for (Image* image : images) {
    auto& pixels = image->pixels();
    group.mergeToRoot(
        std::span(reinterpret_cast<uint8_t*>(pixels.data()), pixels.size() * sizeof(Vec3f)));
    bytes += double(pixels.size() * sizeof(Vec3f));
  }
  mergeStats(group, stats);
  reportMerge(group, bytes, start, reporter);
  return group.isRoot();
}

bool mergeFrameShares(std::vector<uint8_t>& codes, RenderStats& stats, Reporter& reporter) {
  cluster::ProcessGroup& group = cluster::world();
  if (group.size() == 1) return true;
  const auto start = std::chrono::steady_clock::now();
  group.mergeToRoot(codes);
  mergeStats(group, stats);
  reportMerge(group, double(codes.size()), start, reporter);
  return group.isRoot();
}

bool writesJobOutputs() {
  return cluster::world().isRoot();
}

}  // namespace parallax::jobs
