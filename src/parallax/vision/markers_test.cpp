// ArUco markers: the dictionary's cells, and detection in a picture drawn here (each pixel
// supersampled through a known homography), so that the true corners are known exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <vector>

#include "parallax/vision/vision.h"

namespace parallax::vision {
namespace {

constexpr int N = kMarkerCells;

std::vector<uint8_t> rotated(const std::vector<uint8_t>& cells) {  // a quarter clockwise
  std::vector<uint8_t> r(cells.size());
  for (int row = 0; row < N; ++row)
    for (int col = 0; col < N; ++col)
      r[size_t(col * N + (N - 1 - row))] = cells[size_t(row * N + col)];
  return r;
}

TEST(Markers, DictionaryIsOpenCvs4x4With250) {
  EXPECT_EQ(markerDictionarySize(), 250);
  // Pinned, so that every OpenCV version (contrib's aruco, objdetect's) is seen to draw the same.
  const std::vector<uint8_t> first = {0, 0, 0, 0, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 0, 1, 0,
                                      0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(markerCells(0), first);
  const std::vector<uint8_t> last = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0,
                                     0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(markerCells(249), last);
  EXPECT_THROW(markerCells(-1), std::out_of_range);
  EXPECT_THROW(markerCells(250), std::out_of_range);
}

TEST(Markers, CellsHaveABlackBorderAndNoTwoAlikeTurnedAnyWay) {
  std::set<std::vector<uint8_t>> seen;
  for (int id = 0; id < markerDictionarySize(); ++id) {
    std::vector<uint8_t> cells = markerCells(id);
    ASSERT_EQ(cells.size(), size_t(N * N));
    for (int i = 0; i < N; ++i) {
      EXPECT_EQ(cells[size_t(i)], 0) << id;
      EXPECT_EQ(cells[size_t((N - 1) * N + i)], 0) << id;
      EXPECT_EQ(cells[size_t(i * N)], 0) << id;
      EXPECT_EQ(cells[size_t(i * N + N - 1)], 0) << id;
    }
    std::set<std::vector<uint8_t>> turns;
    for (int k = 0; k < 4; ++k, cells = rotated(cells)) turns.insert(cells);
    EXPECT_EQ(turns.size(), 4u) << id;  // no symmetric marker: its turn is always known
    for (const std::vector<uint8_t>& t : turns) EXPECT_TRUE(seen.insert(t).second) << id;
  }
}

// A marker on the plane: its top-left at (x, y) cells, turned `quarters` clockwise.
struct Placed {
  int id;
  double x, y;
  int quarters;
};

// The plane offset (cells) of marker point (u, v) (cells, as drawn), and back.
std::array<double, 2> toPlane(const Placed& m, double u, double v) {
  switch (m.quarters) {
    case 1:
      return {m.x + N - v, m.y + u};
    case 2:
      return {m.x + N - u, m.y + N - v};
    case 3:
      return {m.x + v, m.y + N - u};
    default:
      return {m.x + u, m.y + v};
  }
}
std::array<double, 2> toMarker(const Placed& m, double px, double py) {
  const double dx = px - m.x, dy = py - m.y;
  switch (m.quarters) {
    case 1:
      return {dy, N - dx};
    case 2:
      return {N - dx, N - dy};
    case 3:
      return {N - dy, dx};
    default:
      return {dx, dy};
  }
}

using Matrix = std::array<double, 9>;
std::array<double, 2> apply(const Matrix& h, double x, double y) {
  const double w = h[6] * x + h[7] * y + h[8];
  return {(h[0] * x + h[1] * y + h[2]) / w, (h[3] * x + h[4] * y + h[5]) / w};
}
Matrix inverse(const Matrix& m) {
  const Matrix adj = {
      m[4] * m[8] - m[5] * m[7], m[2] * m[7] - m[1] * m[8], m[1] * m[5] - m[2] * m[4],
      m[5] * m[6] - m[3] * m[8], m[0] * m[8] - m[2] * m[6], m[2] * m[3] - m[0] * m[5],
      m[3] * m[7] - m[4] * m[6], m[1] * m[6] - m[0] * m[7], m[0] * m[4] - m[1] * m[3]};
  return adj;  // a homography is defined up to scale
}

// Four markers, turned every way, on a white plane (cells, y down) seen at a slant: about 20 px a
// cell. Each pixel is the mean of 6 x 6 samples of the plane; `blurred` blurs it further as a
// phone's optics do (two 3 x 3 box filters: about a 1.2 px Gaussian) and adds noise.
const std::vector<Placed> kPlaced = {
    {3, 2, 2, 0}, {17, 14, 3, 1}, {42, 3, 13, 2}, {249, 15, 14, 3}};
const Matrix kPlaneToPhoto = {22, 3, 40, -2, 20, 30, 0.0015, 0.0008, 1};

Photo drawMarkers(bool blurred) {
  std::vector<std::vector<uint8_t>> cells;
  for (const Placed& m : kPlaced) cells.push_back(markerCells(m.id));
  const Matrix back = inverse(kPlaneToPhoto);
  constexpr int kW = 640, kH = 480, kSub = 6;
  constexpr double kBlack = 30, kWhite = 220;
  std::vector<double> grey(size_t(kW) * kH);
  for (int j = 0; j < kH; ++j)
    for (int i = 0; i < kW; ++i) {
      double sum = 0;
      for (int b = 0; b < kSub; ++b)
        for (int a = 0; a < kSub; ++a) {
          const auto [px, py] = apply(back, i + (a + 0.5) / kSub, j + (b + 0.5) / kSub);
          double value = kWhite;
          for (size_t k = 0; k < kPlaced.size(); ++k) {
            const auto [u, v] = toMarker(kPlaced[k], px, py);
            if (u >= 0 && u < N && v >= 0 && v < N)
              value = cells[k][size_t(int(v) * N + int(u))] ? kWhite : kBlack;
          }
          sum += value;
        }
      grey[size_t(j) * kW + size_t(i)] = sum / (kSub * kSub);
    }
  for (int pass = 0; blurred && pass < 2; ++pass) {
    std::vector<double> box = grey;
    for (int j = 1; j + 1 < kH; ++j)
      for (int i = 1; i + 1 < kW; ++i) {
        double sum = 0;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) sum += grey[size_t(j + dj) * kW + size_t(i + di)];
        box[size_t(j) * kW + size_t(i)] = sum / 9;
      }
    grey = box;
  }
  Photo photo{kW, kH, std::vector<uint8_t>(size_t(kW) * kH * 3)};
  uint64_t noise = 12345;
  for (size_t p = 0; p < grey.size(); ++p) {
    noise = noise * 6364136223846793005ull + 1442695040888963407ull;
    const double value = grey[p] + (blurred ? double(noise >> 61) - 3.5 : 0);  // +-3.5 levels
    for (size_t c = 0; c < 3; ++c) photo.rgb[3 * p + c] = uint8_t(std::lround(value));
  }
  return photo;
}

// The largest distance of a found corner from the true one (all markers found, ids right).
double worstCornerError(const Photo& photo) {
  const std::vector<DetectedMarker> found = detectMarkers(photo);
  EXPECT_EQ(found.size(), kPlaced.size());
  if (found.size() != kPlaced.size()) return 1e9;
  const std::array<std::array<double, 2>, 4> drawnCorners = {{{0, 0}, {N, 0}, {N, N}, {0, N}}};
  double worst = 0;
  for (size_t k = 0; k < kPlaced.size(); ++k) {  // both in order of id
    EXPECT_EQ(found[k].id, kPlaced[k].id);
    for (size_t c = 0; c < 4; ++c) {  // in the order drawn, however the marker is turned
      const auto [px, py] = toPlane(kPlaced[k], drawnCorners[c][0], drawnCorners[c][1]);
      const auto [x, y] = apply(kPlaneToPhoto, px, py);
      worst = std::max(worst, std::hypot(found[k].corners[c].x - x, found[k].corners[c].y - y));
    }
  }
  return worst;
}

TEST(Markers, DetectsCornersThroughAPerspectiveWithinATenthOfAPixel) {
  EXPECT_LT(worstCornerError(drawMarkers(false)), 0.1);
}

TEST(Markers, DetectsCornersOfABlurredNoisyPhotoWithinATenthOfAPixel) {
  EXPECT_LT(worstCornerError(drawMarkers(true)), 0.1);
}

TEST(Markers, NoneInABlankPhoto) {
  const Photo blank{64, 48, std::vector<uint8_t>(64 * 48 * 3, 200)};
  EXPECT_TRUE(detectMarkers(blank).empty());
}

}  // namespace
}  // namespace parallax::vision
