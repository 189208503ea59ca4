// Multi-view content: N ordinary camera views of the display's window, alone or tiled into a
// quilt, and their mapping onto the image layer (the paper's Fig. 2 direct mapping).
//
// Conventions (docs/quilts.md): camera views are ordered from the leftmost camera (view 0) to
// the rightmost. A quilt holds them as tiles row by row from the bottom-left: view 0 is the
// bottom-left tile, views increase to the right and then upward. Its file name ends in
// `_qs{columns}x{rows}a{aspect}` before the extension, aspect = width / height of the display the
// views are for (Looking Glass's convention: a 16:9 panel's quilt is a1.7778 whatever its tiles'
// shape; the views are stretched to fill their tiles).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/display/display.h"
#include "parallax/display/display_model.h"
#include "parallax/image/image.h"
#include "parallax/render/render.h"
#include "parallax/scene/scene.h"

namespace parallax {

struct QuiltLayout {
  int columns = 1, rows = 1;
  double aspect = 0;  // width / height of the display the views fill; 0 when not known
  int views() const { return columns * rows; }
};

// "CxR" with both counts positive (and at most 1024); false if malformed.
bool parseColumnsByRows(std::string_view text, int& columns, int& rows);

// The layout in a quilt file's name ("scene_qs5x9a1.7778.png", any number of decimals as
// Looking Glass's tools write them; "scene_qs8x6.png" without an aspect, as in Looking Glass's
// own examples, gives aspect 0). Throws InputError naming the file when the `_qs{C}x{R}` ending
// is absent or malformed.
QuiltLayout parseQuiltName(const std::string& path);

// The aspect as written in quilt names: at most four decimals, no trailing zeros ("1.7778").
std::string formatQuiltAspect(double aspect);
// stem + "_qs{C}x{R}a{aspect}" + extension, e.g. ("quilt", 3x3 a1.7778, ".png"); without the
// `a` part when the aspect is not known (0).
std::string quiltFileName(const std::string& stem, const QuiltLayout& layout,
                          const std::string& extension);
// A quilt video's path as Looking Glass Studio imports it: `path` with the layout's
// _qs{C}x{R}a{aspect} before its extension ("out/turn.mp4" -> "out/turn_qs7x7a1.7778.mp4"), kept
// as it is when its name already ends in that layout (an aspect within 0.5%: a1.78 for 16:9).
// Throws std::invalid_argument (the message, for the caller to put under its own field) when its
// name ends in another quilt's layout.
std::string quiltVideoPath(const std::string& path, const QuiltLayout& layout);

// Tiles `views` (all the same size, leftmost camera first, columns * rows of them) into a quilt.
Image assembleQuilt(const std::vector<Image>& views, int columns, int rows);

// Cuts a quilt into its views (leftmost camera first). Tiles are floor(W / C) x floor(H / R)
// pixels from the bottom-left corner; leftover pixels at the right and top are padding. Their
// shape is free (layout.aspect is the display's, not the tiles'); throws InputError naming
// `source` when the quilt has fewer pixels than tiles.
std::vector<Image> splitQuilt(const Image& quilt, const QuiltLayout& layout,
                              const std::string& source);

// Views the image layer interleaves: round(views), or round(3 views) with subpixel rays.
int interlacedViewCount(const DisplayDesign& design);

// Element k: the design view index (DisplayModel::viewIndex) whose design eye position
// (viewPosition) is k-th from the left. Barrier-back counts views left to right, barrier-front
// right to left.
std::vector<int> designViewsLeftToRight(const DisplayDesign& design);

// Maps camera views (leftmost camera first, interlacedViewCount of them) onto the image layer:
// each is resampled by area to the image layer's resolution if it differs, given to the design
// view seen from its place in the row of eyes, and interleaved (interleaveViews). Throws
// std::invalid_argument for a wrong count (callers check and report it).
Image interlaceCameraViews(const DisplayDesign& design, const std::vector<Image>& cameraViews);

// The eye of camera k of `count`, spread evenly across the view zone S at distance D:
// (e_c + S ((k + 0.5) / count - 0.5), y_e, D). For count = views this is the design eye of the
// k-th view from the left.
Vec3d quiltEyePosition(const DisplayDesign& design, int camera, int count);

// The eye of camera k of `count` for any display: display.eyeAcrossZone((k + 0.5) / count).
Vec3d quiltEyePosition(const DisplayModel& display, int camera, int count);

// Renders the layout's views of the display's window, each tileWidth x tileHeight, from
// quiltEyePosition (one-axis perspective for horizontal-parallax displays), straight into their
// tiles: memory is the quilt's and one view's, whatever the number of tiles.
Image renderQuilt(const Scene& scene, const Accelerator& accelerator, const DisplayModel& display,
                  const RenderSettings& settings, const QuiltLayout& layout, int tileWidth,
                  int tileHeight, RenderStats* stats = nullptr,
                  const ProgressCallback& progress = {});

// Receives view k (leftmost camera first) as soon as it is rendered, with its tile's top-left
// pixel in the quilt (row 0 at the top): the caller keeps it in whatever form it writes.
using QuiltTileSink = std::function<void(int view, int left, int top, const Image& image)>;
// renderQuilt's views, one at a time, handed to `sink` instead of a float quilt: memory is
// one view's plus whatever the sink keeps (render --quilt keeps 8-bit codes: the output's size).
void renderQuiltTiles(const Scene& scene, const Accelerator& accelerator,
                      const DisplayModel& display, const RenderSettings& settings,
                      const QuiltLayout& layout, int tileWidth, int tileHeight,
                      const QuiltTileSink& sink, RenderStats* stats = nullptr,
                      const ProgressCallback& progress = {});

// How views between two given ones are made: the nearest given view, or the two around it
// blended linearly.
enum class ViewResampling { Nearest, Linear };

// Maps a quilt's views onto a lenticular panel as Looking Glass's interlacing shader does: each
// subpixel's view fraction f (viewFraction) picks the views q N - 1/2 lies between (N the
// quilt's views; beyond the first and last view the nearest), blended linearly, each sampled
// where the subpixel sits on the screen. q is the cone fraction of the quilt camera on the design
// line that the subpixel's light reaches (lensQuiltFraction): q = f with the default optics,
// bundles converging at D where the cameras stand. Nearest takes the one view whose window holds
// q, floor(q N) (the shader's unblended mode, "old, studio style"). Returns the panel's picture
// (linear RGB).
Image interlaceQuiltLenticular(const LenticularDesign& design, const std::vector<Image>& views,
                               ViewResampling resampling = ViewResampling::Linear);

// interlaceQuiltLenticular for playing quilt videos (`parallax show`): from a quilt frame of 8-bit
// sRGB codes to the panel's 8-bit sRGB codes, with everything that does not change between frames
// worked out once: each subpixel's two views and their blend, each pixel's bilinear taps inside
// a tile. The blend runs in linear light (codes decoded by table, encoded by linearToSrgb8), as
// interlaceQuiltLenticular on the quilt's decoded views does; the two agree to within one code
// (float against double rounding). The quilt is columns x rows tiles, view 0 at the bottom left
// (splitQuilt), its size a multiple of the layout; rows run in parallel.
class QuiltInterlacer {
 public:
  QuiltInterlacer(const LenticularDesign& design, const QuiltLayout& layout, int quiltWidth,
                  int quiltHeight, ViewResampling resampling = ViewResampling::Linear);
  int panelWidth() const { return panelWidth_; }
  int panelHeight() const { return panelHeight_; }
  // The table's bytes, for memory estimates.
  static double bytesPerPanelPixel();
  // quilt: quiltWidth x quiltHeight RGB triples, row 0 at the top; panel: panelWidth x
  // panelHeight RGB triples, written whole.
  void interlace(const uint8_t* quilt, uint8_t* panel, int threads = 0) const;

 private:
  struct PixelTaps {
    int32_t offset;       // of the top-left tap from a tile's top-left corner, in quilt pixels
    int32_t right, down;  // the other taps' steps (0 where the tile's edge clamps them)
    float tx, ty;
  };
  struct SubpixelViews {
    uint16_t below, above;  // views, blended (1 - t) below + t above
    float t;
  };
  int panelWidth_ = 0, panelHeight_ = 0, quiltWidth_ = 0;
  std::vector<int64_t> tileOrigin_;   // view k's top-left corner, in quilt pixels
  std::vector<PixelTaps> taps_;       // per panel pixel
  std::vector<SubpixelViews> views_;  // per panel subpixel (pixel * 3 + channel)
};

// Resamples camera views (leftmost first) to `count` views across the same zone: view k of
// `count` at (k + 1/2) / count of the way across takes the nearest camera view, or blends the
// two around it linearly.
std::vector<Image> resampleViews(const std::vector<Image>& views, int count,
                                 ViewResampling resampling);

// Renders `count` off-axis views of the display's window (WindowCamera, sheared frustum) of
// width x height pixels from quiltEyePosition, leftmost camera first. Slit masks get the
// one-axis perspective of renderDirectMapping (identical for eyes on the view line).
std::vector<Image> renderQuiltViews(const Scene& scene, const Accelerator& accelerator,
                                    const DisplayDesign& design, const RenderSettings& settings,
                                    int count, int width, int height, RenderStats* stats = nullptr,
                                    const ProgressCallback& progress = {});

}  // namespace parallax
