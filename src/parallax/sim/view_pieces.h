// The pieces an output pixel of a simulated view is made of along one axis: shared by the
// simulator (simulator.cpp) and the layer solvers' operator (seen_layers.h). Internal to sim.
#pragma once

#include <cstdint>
#include <vector>

#include "parallax/core/math.h"
#include "parallax/display/display.h"

namespace parallax {

// One piece of an output pixel along one axis: the front-layer cell and the rear-layer cell the
// eye's lines meet over that piece, and the piece's share of the pixel.
struct Piece {
  int front = 0, rear = 0;
  float weight = 0;
};

// The pieces of output pixels 0 .. count-1 along one axis, in order, with start[i] .. start[i+1]
// those of pixel i. A position t in [0, 1] across the front layer lies in front cell
// floor(t frontCells) and meets the rear layer at rear cell coordinate u(t) = u0 + du t (affine:
// the eye's line through the front point, continued by the gap). samplesPerAxis 0: the pieces
// between every front and rear cell edge inside the pixel, weighted by length (the exact
// integral of the two box-pixel layers' product). n > 0: n point samples at the stratum
// centres, 1/n each. A rear cell outside [0, rearCells) becomes `outside`.
void piecesAlongAxis(int count, int frontCells, int rearCells, double u0, double du,
                     int samplesPerAxis, int outside, std::vector<Piece>& pieces,
                     std::vector<uint32_t>& start);

// The points a pupil of `diameterMm` around `eye` is sampled at, in the plane z = eye.z: a
// Fibonacci (Vogel) spiral of `samples` points (equal-area rings, points a golden angle apart:
// deterministic, evenly spread); the eye itself for a pinhole eye (diameter 0).
std::vector<Vec3d> pupilPoints(const Vec3d& eye, double diameterMm, int samples);

// The channels stripe s (0, 1, 2 from the left) of a pixel passes under colour filters: a
// one in the channel of that stripe.
inline Vec3f stripePasses(SubpixelOrder order, int stripe) {
  Vec3f pass(0.0f);
  pass[order == SubpixelOrder::BGR ? 2 - stripe : stripe] = 1.0f;
  return pass;
}

}  // namespace parallax
