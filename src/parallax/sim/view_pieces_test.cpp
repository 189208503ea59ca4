// The pieces of an output pixel against brute-force point sampling of the same lines.
#include "parallax/sim/view_pieces.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

namespace parallax {
namespace {

// The share of output pixel i that meets each (front cell, rear cell) pair, by 20000 point
// samples: t in pixel i lies in front cell floor(t F) and meets rear cell floor(u0 + du t).
std::map<std::pair<int, int>, double> sampled(int i, int count, int frontCells, int rearCells,
                                              double u0, double du) {
  std::map<std::pair<int, int>, double> share;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const double t = (i + (k + 0.5) / n) / count;
    const int front = std::min(int(std::floor(t * frontCells)), frontCells - 1);
    const double u = std::floor(u0 + du * t);
    const int rear = u >= 0 && u < rearCells ? int(u) : -1;
    share[{front, rear}] += 1.0 / n;
  }
  return share;
}

TEST(ViewPieces, ExactPiecesAreTheShareOfEveryCellPair) {
  struct Case {
    int count, frontCells, rearCells;
    double u0, du;
  };
  for (const Case& c : {Case{12, 12, 12, 0.3, 12.06}, Case{10, 20, 15, -2.2, 17.5},
                        Case{7, 7, 9, 1.7, -6.4}, Case{16, 8, 8, -0.5, 8.0}}) {
    std::vector<Piece> pieces;
    std::vector<uint32_t> start;
    piecesAlongAxis(c.count, c.frontCells, c.rearCells, c.u0, c.du, 0, -1, pieces, start);
    ASSERT_EQ(start.size(), size_t(c.count) + 1);
    for (int i = 0; i < c.count; ++i) {
      std::map<std::pair<int, int>, double> exact;
      double total = 0;
      for (uint32_t k = start[size_t(i)]; k < start[size_t(i) + 1]; ++k) {
        exact[{pieces[k].front, pieces[k].rear}] += pieces[k].weight;
        total += pieces[k].weight;
      }
      EXPECT_NEAR(total, 1.0, 1e-6) << "pixel " << i;
      for (const auto& [pair, share] : sampled(i, c.count, c.frontCells, c.rearCells, c.u0, c.du))
        EXPECT_NEAR(exact[pair], share, 2e-4)
            << "pixel " << i << " cells " << pair.first << "," << pair.second;
    }
  }
}

TEST(ViewPieces, PointSamplesSitAtStratumCentres) {
  std::vector<Piece> pieces;
  std::vector<uint32_t> start;
  piecesAlongAxis(4, 4, 4, 0.0, 4.0, 3, 99, pieces, start);
  ASSERT_EQ(pieces.size(), 12u);
  for (const Piece& p : pieces) EXPECT_FLOAT_EQ(p.weight, 1.0f / 3.0f);
  // The rear cell outside the panel is the caller's `outside`.
  piecesAlongAxis(1, 1, 2, 5.0, 1.0, 1, 99, pieces, start);
  EXPECT_EQ(pieces.front().rear, 99);
}

}  // namespace
}  // namespace parallax
