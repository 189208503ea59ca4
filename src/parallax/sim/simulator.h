// What an eye sees on a two-layer display: the model of ../shared/reference/geometry.md,
// "Seeing the display". The eye E looks through the front point F (z = 0) on to the rear point
// R (z = -g) of the same line,
//
//     R = E + (F - E) (E.z + g) / E.z,
//
// and perceives backlight * T_rear(R) * T_front(F) in linear light. Both layers are LCDs:
// nearest-pixel boxes, optionally split into R, G, B colour-filter stripes; outside a panel the
// transmittance is 0. Frame and layer order as in docs/display-geometry.md.
#pragma once

#include <optional>
#include <vector>

#include "parallax/display/display.h"
#include "parallax/display/lenticular.h"
#include "parallax/image/image.h"

namespace parallax {

struct SimulationOptions {
  // Output pixels covering the front layer's rectangle like a camera film (row 0 at the top);
  // 0 = the front layer's resolution.
  int width = 0, height = 0;
  // 0: each output pixel's area integrated exactly (the product of the two layers' box pixels,
  // piecewise constant along the eye's lines, summed over the pieces). n x n: point samples at
  // the stratum centres (1 = the pixel centre), which alias against a mask whose openings are
  // one pixel wide (docs/simulator.md); must then be a square (1, 4, 9, 16, ...).
  int samplesPerPixel = 0;
  // 0: a pinhole eye. Otherwise the view is averaged over pupilSamples points of a disk of this
  // diameter in the plane z = eye.z (a Fibonacci spiral: deterministic, evenly spread).
  double pupilDiameterMm = 0.0;
  int pupilSamples = 16;
  // Gaussian blur of the rear layer (standard deviation, mm): the diffuser/polariser foil the
  // paper blames for cross-talk.
  double diffuserSigmaMm = 0.0;
  // Split each pixel of a layer whose panel has an RGB or BGR subpixel order into three
  // vertical stripes dx/3 wide; stripe c passes only channel c of the pixel's value (a white
  // pixel seen through its red stripe is (1, 0, 0)). Sample each front pixel at least three
  // times across (width = 3 x the panel's, or samplesPerPixel >= 9), or every sample meets the
  // middle stripe.
  bool colourFilters = false;
  // Divide by the mean transmittance of the mask layer and of the colour filters (1/3 for each
  // filtered layer), so that a white image looks white whatever the aperture ratio; false: raw.
  bool normalise = true;
  // With normalise: divide by this instead of the mask's mean transmittance (0: the mean).
  // Optimised layers record the brightness they aimed at here (render --layers: the slit mask's
  // mean times the gain), so that they compare with the ideal views at that brightness.
  double normalisation = 0.0;
  Vec3f backlight{1.0f};
  int threads = 0;  // 0 = hardware concurrency; the result does not depend on it
  // Lenticular panels: read the panel under these optics instead of its design's (the readings
  // of docs/lenticular.md, "The optics"); unset: the design's own.
  std::optional<LensOptics> lensOptics;
};

// Layer contents as linear transmittance in [0, 1], at the layers' native resolutions.
struct LayerImages {
  Image image;
  Image mask;
};

class DisplaySimulator {
 public:
  // Throws InputError naming "/image_layer" or "/mask_layer" when an image's size differs from
  // its panel, and the option's key when an option is out of range. Blurs the rear layer here,
  // once, not per view.
  DisplaySimulator(const DisplayDesign& design, LayerImages layers,
                   const SimulationOptions& options);

  // What an eye at eyeMm (display millimetres, z > 0) sees, in linear light.
  Image view(const Vec3d& eyeMm) const;

  // The view at the display's resolution: atDisplayResolution(design, view(eyeMm)), what the
  // dense measure compares. With exact integration, the front layer's resolution and slits
  // (viewsThroughSeenLayers) it is made in one pass of SeenLayers' vectorised rows
  // (seen_layers.h: the same operator, equal to float rounding; colour filters, a diffuser and
  // a pupil too), otherwise as written.
  Image seen(const Vec3d& eyeMm) const;
  bool viewsThroughSeenLayers() const { return viewsThroughSeenLayers_; }

  // The points the eye's pupil is sampled at: the eye itself for a pinhole eye.
  std::vector<Vec3d> pupilPoints(const Vec3d& eyeMm) const;

  double maskMeanTransmittance() const { return maskMean_; }
  int outputWidth() const { return width_; }
  int outputHeight() const { return height_; }
  const DisplayDesign& design() const { return design_; }

 private:
  // One panel as the eye meets it: a row-major grid of cells (pixels, or colour stripes),
  // each row ending in one extra zero cell that lookups beyond the panel's sides point to.
  struct Layer {
    std::vector<Vec3f> cells;
    int columns = 0, rows = 0;
    bool striped = false;  // colour-filter stripes, three cells per pixel
    double cellWidthMm = 0, cellHeightMm = 0;
    const Vec3f* row(int r) const { return cells.data() + size_t(r) * size_t(columns + 1); }
  };
  static Layer makeLayer(const Image& image, const Panel& panel, bool colourFilters);
  static void blur(Layer& layer, double sigmaMm, int threads);

  DisplayDesign design_;
  SimulationOptions options_;
  Layer front_, rear_;
  double maskMean_ = 0;
  bool viewsThroughSeenLayers_ = false;
  double scale_ = 1;  // normalisation / pupil samples
  // seen() through SeenLayers: the front layer's pixels when it has colour filters (SeenLayers
  // passes them through the stripes), and the normalisation without the stripes' 1/3 and the
  // pupil's 1/N, which SeenLayers undoes and averages itself.
  Image frontPixels_;
  double seenScale_ = 1;
  int width_ = 0, height_ = 0, threads_ = 1;
};

// The barrier's display resolution (SimulatedDisplay::atDisplayResolution): a box one screen
// period across (and, for pinhole grids, one vertical period down).
Image atDisplayResolution(const DisplayDesign& design, const Image& image);

}  // namespace parallax
