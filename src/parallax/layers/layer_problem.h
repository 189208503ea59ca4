// Content-adaptive layers: the layer images that best show a set of target views, solved over
// eyes spread across the view zone (docs/content-adaptive.md). The model is the simulator's own
// view (sim/seen_layers.h): at eye e the viewer sees V_e = B P_e(front, rear), bilinear in the
// two layers; T time-multiplexed frame pairs are seen as their average, as the eye integrates
// them. Two solvers minimise
//
//     E = 1/2 sum_e |V_e - t_e|^2,   every layer pixel in [0, 1] (linear transmittance),
//
// (or, for the image layer, the same on sRGB-encoded values: TrainingView::encodingScale),
//   - optimizeImageLayer: the mask fixed (the paper's slits), V is linear in the image layer and
//     E a least-squares problem in it (on sRGB values, solved by Gauss-Newton steps): projected
//     gradient descent, preconditioned by 1 / (sum_e A_e^T W_e A_e 1), with the step that
//     minimises E's Gauss-Newton model on the plane of the projected direction and the previous
//     step, halved until E decreases (so E never increases); each image row on its own where
//     the rows are independent (the image in front);
//   - factorizeLayers: both layers of T frames by weighted non-negative multiplicative updates
//     (Lee and Seung 2001; Lanman et al. 2010, HR3D, eq. 7-8; Wetzstein et al. 2012, Tensor
//     Displays): x <- clamp(x * (A^T t) / (A^T V), 0, 1) for all frames' images, then all their
//     masks. Each update minimises a separable upper bound of E, and clamping a separable
//     quadratic's minimiser to [0, 1] keeps it the bound's minimiser over the box, so E never
//     increases either.
// This header is the problem both solvers share (the training eyes, the frames, E); the solvers
// are image_layer_solver.h and layer_factorization.h, their shared numerics layer_numerics.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "parallax/core/memory.h"
#include "parallax/image/image.h"
#include "parallax/sim/seen_layers.h"

namespace parallax {

// One training eye: what it sees of the layers, and what it should see (through B, in the
// layers' physical units: the ideal view times the brightness the layers aim at).
struct TrainingView {
  SeenLayers seen;
  Image target;
  // > 0 (optimizeImageLayer only): errors between the sRGB encodings of V / encodingScale and
  // target / encodingScale (the layers' brightness), the dense measure's own squared error,
  // solved by Gauss-Newton steps. 0: errors in linear light.
  float encodingScale = 0.0f;
  // The target kept in 16 bits per channel (3 per pixel, row by row) when encodeTarget() made
  // it, half the bytes of the float target it replaces (whose first touch of memory is a
  // second or more of a 1080p solve's ideal views here: docs/content-adaptive.md, "Cost"):
  //   - sRGB errors (encodingScale > 0): round(65535 S(target / encodingScale)), as those errors
  //     read it, one encoding fewer per pixel and pass (the same errors to within 1/131070 in S);
  //   - linear light (encodingScale = 0): round(target / linearUnit), linearUnit = the target's
  //     largest value / 65535: within linearUnit / 2 of it, a ten-thousandth of the largest
  //     value, far below the layers' own error (docs/content-adaptive.md, "Targets in 16 bits").
  // Empty: the solvers read `target`.
  UninitializedLargeVector<uint16_t> encodedTarget = {};
  float linearUnit = 0.0f;
  // The view row that the target's first row is (optimizeImageLayerByBands: the targets of one
  // band of rows at a time; 0 otherwise, the target being the whole view).
  int firstTargetRow = 0;
  // factorizeLayers' form of the target (encodeBoxedTarget, linear light): the codes hold B^T t
  // instead of t (round(B^T t / linearUnit), B^T t >= 0), which is all its multiplicative
  // updates read of the target (their numerators: one box fewer per eye, row and pass), and
  // rowTargetSquares[j] = |t_j|^2 of each row j, from which with the image in front (P_j =
  // sum over frames of front_j .* m_j / T) E needs no t either:
  //     E_j = |V_j - t_j|^2 / 2 = |V_j|^2 / 2 - <P_j, B^T t_j> + |t_j|^2 / 2.
  // Each row j's codes are in its own unit rowUnits[j] (its largest B^T t / 65535), so that a
  // band of rows can be encoded as soon as it is rendered (IdealViewBands::wholeBoxedTargets).
  bool boxedTarget = false;
  std::vector<double> rowTargetSquares = {};
  std::vector<float> rowUnits = {};
  // Fills encodedTarget (and linearUnit) and frees target.
  void encodeTarget(int threads = 0);
  // The same with B^T t in the codes (boxedTarget), for factorizeLayers; linear light only.
  void encodeBoxedTarget(int threads = 0);
  // Rows firstRow .. firstRow + count - 1 of the linear target (`rows`, the view's width each,
  // overwritten) into the boxed codes, their units and squares: encodeBoxedTarget a band of rows
  // at a time, once startBoxedTarget has sized them for the whole view.
  void startBoxedTarget();
  void encodeBoxedRows(Vec3f* rows, int firstRow, int count);
  // Row j of the target in linear light, decoded when it is kept in 16 bits (into `row`, which
  // must hold the view's width; the pointer returned is `row`'s or the target's own). Not for a
  // boxed target.
  const Vec3f* linearTargetRow(int j, Vec3f* row) const;
  // Row j of B^T t into `out`: decoded (boxedTarget), or the linear target's row through B^T
  // (`scratch`: the view's width, for its decoding).
  void boxedTargetRow(int j, Vec3f* out, Vec3f* scratch) const;
  // The whole target in linear light: `target`, or the codes decoded into `holder`.
  const Image& linearTarget(Image& holder, int threads = 0) const;
};

// TrainingView::encodedTarget's unit: S in [0, 1] as 0 .. 65535.
inline constexpr float kEncodedUnit = 65535.0f, kInverseEncodedUnit = 1.0f / 65535.0f;
// The targets' codes stream from memory, a row of each eye in turn: the loops that read them
// ask for them this many codes ahead (a kilobyte: their loads stalled the loops otherwise, the
// prefetcher starting anew with each row).
inline constexpr size_t kPrefetchCodes = 512;

// One frame of layers (image and mask panels), linear transmittance.
struct LayerFrame {
  Image image, mask;
};

// The rows of a band of optimizeImageLayerByBands (render's optimized-image: training.h,
// solvesByBands): four of the renderer's tile rows. The solve keeps each eye's mask as seen in
// colour (three floats a pixel: through colour filters) for bands of at most this many rows.
inline constexpr int kTargetBandRows = 64;

// A diffuser foil between the panels (sim/diffuser.h): the rear layer is seen blurred by G, a
// Gaussian of sigmaMm over the rear panel's pixels (pitchMm apart). The solvers then fit
// V = B P(front, G rear): G in the views, and G^T = G on the rear layer's gradient.
struct RearDiffuser {
  double sigmaMm = 0, pitchMm = 0;
  // The rear panel's colour-filter stripes when the eyes see through the filters (None: they
  // do not, or the panel has none): the foil blurs the light the stripes pass, so the rear
  // layer is seen as its stripe cells blurred (sim/diffuser.h, stripedDiffuserBlurred: three
  // times as wide), which the views' SeenLayers read as such (SeenOptics::rearStripeCells).
  SubpixelOrder stripes = SubpixelOrder::None;
  bool active() const { return sigmaMm > 0 && pitchMm > 0; }
  bool striped() const { return active() && stripes != SubpixelOrder::None; }
  // G (G S when striped) applied to a rear layer: the layer as the eyes see it.
  Image apply(const Image& layer, int threads = 0) const;
  // Its transpose on a gradient of the seen layer: G itself (G is symmetric), S^T G when
  // striped.
  Image applyTransposed(const Image& seen, int threads = 0) const;
  // The seen layer's columns for a rear layer of `columns`.
  int seenColumns(int columns) const { return striped() ? 3 * columns : columns; }
};

struct SolveReport {
  std::vector<double> objective;  // E / (pixels x channels x eyes): before, then per iteration
  int iterations = 0;             // iterations run (fewer when a step no longer lowers E)
  // Passes over every training eye's target (an objective, a gradient, a curvature, an update
  // of one layer: each reads every target once), for `bench --layers`.
  int passes = 0;
};

// E / (view pixels x 3 x eyes) of `frames` seen as their average (through `diffuser`).
double layerObjective(const std::vector<TrainingView>& views, const std::vector<LayerFrame>& frames,
                      int threads = 0, const RearDiffuser& diffuser = {});

// Told as a solve goes, for progress: (iterations done, iterations asked, objective), or,
// where the rows are solved on their own, (rows done, rows, the objective of those rows).
using SolveProgress = std::function<void(int done, int total, double objective)>;

}  // namespace parallax
