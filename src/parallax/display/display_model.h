// The display as one concept (docs/architecture.md, "One display, every kind"). Whatever its
// optics, a glasses-free display shows the scene through a window (its front surface) to eyes
// in a view zone, from a film of columns (panel pixels, or one colour channel each) in which
// every sample is one ray. The display camera, the display render, the simulator's dispatch and
// the quilt paths ask only this. A parallax barrier (two stacked LCDs, display.h) and a slanted
// lenticular sheet (lenticular.h) implement it; a third kind is one more class and its tests.
//
// Frame: display millimetres, x right, y up, z toward the viewer, the front surface at z = 0
// centred on the origin (docs/display-geometry.md).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "parallax/core/math.h"
#include "parallax/display/display.h"
#include "parallax/display/lenticular.h"
#include "parallax/display/view_filter.h"
#include "parallax/image/image.h"

namespace parallax {

// The window a viewer looks through: the front surface's size, and the eye that content is
// framed for (the view-zone centre at the design distance; its y is the view line's height).
struct DisplayWindow {
  double widthMm = 0, heightMm = 0;
  Vec3d eyeMm;
};

// The film the display camera renders: `columns` x `rows` samples of one ray column each. With
// subpixel columns, film column c carries only colour channel channelOfColumn(c) of panel pixel
// c / 3; otherwise film and panel pixels are the same.
struct FilmLayout {
  int columns = 0, rows = 0;
  int panelWidth = 0, panelHeight = 0;
  bool subpixelColumns = false;
};

// A display ray in display millimetres: it starts on the viewer's side and runs toward the
// display, direction.z = -1.
struct DisplayRay {
  Vec3d origin, direction;
};

// A panel's or a picture's size in pixels.
struct PanelSize {
  int width = 0, height = 0;
};

// A quilt's layout: views in columns x rows.
struct QuiltShape {
  int columns = 0, rows = 0;
};

// One line of the design report: a named figure and its unit ("" for a plain number).
struct DesignFigure {
  std::string key;
  double value = 0;
  std::string unit;
};

// Other: a kind outside the two that have files (a model made in code, such as the tests'
// third kind); the runners ask it only what DisplayModel answers.
enum class DisplayKind { Barrier, Lenticular, Other };
const char* displayKindName(DisplayKind kind);

class DisplayModel {
 public:
  virtual ~DisplayModel() = default;

  virtual DisplayKind kind() const = 0;
  // The file it was read from ("<built-in>", a preset's name), for messages.
  virtual const std::string& source() const = 0;
  virtual DisplayWindow window() const = 0;
  virtual FilmLayout film() const = 0;
  // The colour channel (0 R, 1 G, 2 B) film column `column` carries (subpixel columns only).
  virtual int channelOfColumn(int column) const = 0;

  // The ray of a film sample at continuous film position (x, y) (pixel (i, j) covers
  // [i, i+1) x [j, j+1), y down) with angular sample (u, v) in [0, 1)^2, spread by the render's
  // view filter (display/view_filter.h); u = v = 0.5 at a pixel centre is the central ray.
  virtual DisplayRay ray(double filmX, double filmY, double u, double v) const = 0;
  // Sixteen at once (the render loop's packets); the default calls ray() per lane.
  virtual void rays16(const float filmX[16], const float filmY[16], const float u[16],
                      const float v[16], double origin[3][16], double direction[3][16]) const;
  // True when every sample of a film pixel is its central ray (the view filter none): more than
  // one sample per pixel would trace the same ray again.
  virtual bool centralRayOnly() const = 0;
  // True when the rays of one film column fan through one aperture (a slit), so that the
  // render loop's packets should run down a column and share their jitter.
  virtual bool columnFans() const = 0;

  // Views: the display's angular samples. viewCount() design eyes sit evenly across the view
  // zone at the design distance (left to right, except a barrier-front's, which counts them from
  // the right); viewIndex says which one a film column serves.
  virtual int viewCount() const = 0;
  virtual int viewIndex(int column, int row) const = 0;
  virtual Vec3d viewPosition(int view) const = 0;
  virtual double viewZoneWidthMm() const = 0;
  // The eye a fraction t of the way across the view zone at the design distance, from its left
  // edge (t = 0) to its right (t = 1): even steps across a barrier's zone, even steps in angle
  // across a lenticular's cone. Quilt cameras and sweeps stand here.
  virtual Vec3d eyeAcrossZone(double t) const = 0;
  // Whether slit displays' one-axis perspective applies to the ideal view (the eye's height
  // does not change what it sees); false for displays with vertical parallax.
  virtual bool horizontalParallaxOnly() const = 0;
  // The eye whose picture of the scene the display means to show an eye at `eyeMm`: the eye
  // itself unless the render compresses depth (a barrier's virtual gap, display_camera.h).
  virtual Vec3d intendedEye(const Vec3d& eyeMm) const { return eyeMm; }

  // A second layer whose picture is fixed by the optics (a barrier's mask); none otherwise.
  virtual bool hasMaskLayer() const { return false; }
  // Each mask pixel's open fraction by area, grey linear transmittance (empty without one).
  virtual Image maskLayer() const { return {}; }

  // The figures `design` prints and render.json records.
  virtual std::vector<DesignFigure> designReport() const = 0;

  // The panel an eye looks at first, whose resolution a viewer's picture of the display is made
  // at (view --display-eye, simulate): a barrier's front layer; the panel itself otherwise.
  virtual PanelSize viewerPanel() const { return {film().panelWidth, film().panelHeight}; }
  // A diffuser foil between the layers (a Gaussian's sigma, mm): 0 without one.
  virtual double diffuserSigmaMm() const { return 0.0; }
  // `render --quilt`'s layout when none is asked (a device's own quilt, or one row of the
  // views), and one view's size in a quilt of `columns` x `rows`.
  virtual QuiltShape defaultQuilt() const { return {viewCount(), 1}; }
  virtual PanelSize quiltTile(int /*columns*/, int /*rows*/) const {
    return {film().panelWidth, film().panelHeight};
  }
  // Views a render by direct mapping takes per panel pixel column (the usual practice's
  // baseline, one ordinary view each: a barrier's screen period); 1 for a display that does
  // not interleave views by columns.
  virtual double directMappingViews() const { return 1.0; }
  // The dense measure's eyes (quality/viewer_quality.h, docs/simulator.md): the views it counts
  // them by (a barrier's pixel views: one per image pixel column of a screen period), the eye
  // `inView` (0 to 1) of the way across view `view`'s window at `distance` times the design
  // distance, and each view's design eye.
  virtual int denseViewCount() const { return viewCount(); }
  virtual Vec3d denseEye(int view, double inView, double distance) const {
    const Vec3d centre = window().eyeMm;
    const Vec3d e = eyeAcrossZone((view + inView) / viewCount());
    return {centre.x + (e.x - centre.x) * distance, e.y, e.z * distance};
  }
  virtual std::vector<Vec3d> denseDesignEyes() const {
    std::vector<Vec3d> eyes;
    for (int v = 0; v < viewCount(); ++v) eyes.push_back(viewPosition(v));
    return eyes;
  }
  // What the display's file was recognised as, where that decides its defaults (a lenticular
  // unit's own file: which Looking Glass device, hence its quilt); "" for nothing to say.
  virtual std::string deviceNote() const { return ""; }
  // What the render's summary line says of the display first ("": nothing), e.g. a lens
  // sheet's pixels per lens and view cone.
  virtual std::string summaryClause() const { return ""; }

  // The kind-specific description, for the parts that are one kind's own (the two-layer
  // simulator, the lenticular interlacer); null for the other kinds.
  virtual const DisplayDesign* barrierDesign() const { return nullptr; }
  virtual const LenticularDesign* lenticularDesign() const { return nullptr; }
};

// The two kinds. `filter` is the render's prefilter (a render setting, not part of the display).
std::unique_ptr<DisplayModel> makeBarrierDisplay(const DisplayDesign& design,
                                                 const ViewFilter& filter = {});
std::unique_ptr<DisplayModel> makeLenticularDisplay(const LenticularDesign& design,
                                                    const ViewFilter& filter = {});

// A barrier design's window (the front layer, framed for the view-zone centre).
DisplayWindow displayWindow(const DisplayDesign& design);

// A lenticular panel's window, framed for the design viewer straight in front of it.
DisplayWindow displayWindow(const LenticularDesign& design);

// The eye whose picture of the scene a barrier rendered with a virtual gap g' != g (and
// D' = D) shows to an eye at `eyeMm` (display mm): the camera's rays, traced in the scene,
// meet the eye plane z = D at e_c + r (E - e_c) instead of E, r = g (g' + D) / (g' (g + D))
// for barrier-back and g / g' for barrier-front, and a point at z lands at
// z' = z D / (r (D - z) + z), x' = e_c + r (x - e_c) z' / z: the view-zone centre is its own
// virtual eye. The eye itself for g' = g or D' != D (docs/display-geometry.md, "Depth budget").
Vec3d virtualEye(const DisplayDesign& design, const Vec3d& eyeMm);

// The barrier's mask layer as an Image: MaskGeometry(design).rasterize() in every channel.
Image maskLayerImage(const DisplayDesign& design);

}  // namespace parallax
