#include "parallax/sim/view_pieces.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace parallax {

namespace {

constexpr int kMaxRearCellsPerPixel = 64;

}  // namespace

void piecesAlongAxis(int count, int frontCells, int rearCells, double u0, double du,
                     int samplesPerAxis, int outside, std::vector<Piece>& pieces,
                     std::vector<uint32_t>& start) {
  pieces.clear();
  start.assign(size_t(count) + 1, 0);
  // The front cells pixel i overlaps, exactly (integers): first = floor(i F / N),
  // last = ceil((i + 1) F / N) - 1. A piece's midpoint rounded near the pixel's edge stays in them.
  int firstCell = 0, lastCell = 0;
  const auto add = [&](double t, float weight) {
    Piece piece;
    piece.front = std::clamp(int(std::floor(t * frontCells)), firstCell, lastCell);
    const double u = std::floor(u0 + du * t);
    piece.rear = u >= 0 && u < rearCells ? int(u) : outside;
    piece.weight = weight;
    pieces.push_back(piece);
  };
  std::vector<double> edges;
  for (int i = 0; i < count; ++i) {
    start[size_t(i)] = uint32_t(pieces.size());
    firstCell = int(int64_t(i) * frontCells / count);
    lastCell = int((int64_t(i + 1) * frontCells - 1) / count);
    const double t0 = double(i) / count, t1 = double(i + 1) / count;
    // An eye almost touching the display stretches one output pixel over thousands of rear
    // cells; there the exact pieces would cost without limit, and kMaxRearCells point samples
    // per pixel are as good as the eye can tell.
    const bool pointSampled =
        samplesPerAxis > 0 || std::abs(du) * (t1 - t0) > double(kMaxRearCellsPerPixel);
    if (pointSampled) {
      const int n = samplesPerAxis > 0 ? samplesPerAxis : kMaxRearCellsPerPixel;
      for (int k = 0; k < n; ++k) add(t0 + (t1 - t0) * (k + 0.5) / n, 1.0f / float(n));
      continue;
    }
    edges.assign({t0, t1});
    for (int k = int(std::ceil(t0 * frontCells)); k < t1 * frontCells; ++k)
      if (k > t0 * frontCells) edges.push_back(double(k) / frontCells);
    if (du != 0) {
      const double ua = u0 + du * t0, ub = u0 + du * t1;
      for (double m = std::ceil(std::min(ua, ub)); m < std::max(ua, ub); ++m)
        edges.push_back((m - u0) / du);
    }
    std::sort(edges.begin(), edges.end());
    for (size_t e = 0; e + 1 < edges.size(); ++e) {
      const double a = std::clamp(edges[e], t0, t1), b = std::clamp(edges[e + 1], t0, t1);
      if (b > a) add(0.5 * (a + b), float((b - a) / (t1 - t0)));
    }
  }
  start[size_t(count)] = uint32_t(pieces.size());
}

std::vector<Vec3d> pupilPoints(const Vec3d& eye, double diameterMm, int samples) {
  if (!(diameterMm > 0)) return {eye};
  const double goldenAngle = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  std::vector<Vec3d> points(static_cast<size_t>(samples));
  for (int i = 0; i < samples; ++i) {
    const double r = 0.5 * diameterMm * std::sqrt((i + 0.5) / samples);
    const double angle = i * goldenAngle;
    points[size_t(i)] = {eye.x + r * std::cos(angle), eye.y + r * std::sin(angle), eye.z};
  }
  return points;
}

}  // namespace parallax
