#include "parallax/sim/simulator.h"

#include "parallax/sim/diffuser.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "parallax/core/error.h"
#include "parallax/core/parallel.h"
#include "parallax/image/metrics.h"
#include "parallax/sim/seen_layers.h"
#include "parallax/sim/view_pieces.h"

namespace parallax {

namespace {

// Rows in bands of kRowGrain over the workers (core/parallel.h). Every row is computed the
// same way whichever band holds it, so results do not depend on the thread count.
constexpr int64_t kRowGrain = 8;

template <class Body>
void forRows(int rows, int threads, const Body& body) {
  parallelFor(rows, threads, kRowGrain,
              [&](int64_t begin, int64_t end) { body(int(begin), int(end)); });
}

std::string size(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

void checkSize(const DisplayDesign& design, const Image& image, const Panel& panel,
               const std::string& key, const std::string& what) {
  if (image.width() != panel.width || image.height() != panel.height)
    throw InputError(design.spec.source, key + "/resolution",
                     "the " + what + " is " + size(image.width(), image.height()) +
                         " pixels but its panel is " + size(panel.width, panel.height));
}

void checkOptions(const SimulationOptions& o) {
  const auto fail = [](const std::string& key, const std::string& message) {
    return InputError("simulation", key, message);
  };
  if (o.width < 0 || o.height < 0) throw fail("/width", "must be 0 (native) or positive");
  const int n = int(std::lround(std::sqrt(double(std::max(o.samplesPerPixel, 0)))));
  if (o.samplesPerPixel < 0 || n * n != o.samplesPerPixel)
    throw fail("/samples_per_pixel", "must be 0 (exact) or a square (1, 4, 9, 16, ...)");
  if (!(o.pupilDiameterMm >= 0) || !std::isfinite(o.pupilDiameterMm))
    throw fail("/pupil_diameter_mm", "must be 0 (a pinhole eye) or positive");
  if (o.pupilSamples < 1) throw fail("/pupil_samples", "must be at least 1");
  if (!(o.diffuserSigmaMm >= 0) || !std::isfinite(o.diffuserSigmaMm))
    throw fail("/diffuser_sigma_mm", "must be 0 or positive");
  if (o.threads < 0) throw fail("/threads", "must be 0 (all cores) or positive");
  if (!(o.normalisation >= 0) || !std::isfinite(o.normalisation))
    throw fail("/normalisation", "must be 0 (the mask's mean) or positive");
}

void checkEye(const Vec3d& eye) {
  if (!(eye.z > 0) || !std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z))
    throw InputError("simulation", "/eye", "the eye must be in front of the display (z > 0)");
}

}  // namespace

DisplaySimulator::Layer DisplaySimulator::makeLayer(const Image& image, const Panel& panel,
                                                    bool colourFilters) {
  Layer layer;
  const bool stripes = colourFilters && panel.subpixels != SubpixelOrder::None;
  const int perPixel = stripes ? 3 : 1;
  layer.striped = stripes;
  layer.columns = image.width() * perPixel;
  layer.rows = image.height();
  layer.cellWidthMm = panel.pitchMm / perPixel;
  layer.cellHeightMm = panel.pitchMm;
  layer.cells.assign(size_t(layer.columns + 1) * size_t(layer.rows), Vec3f(0.0f));
  for (int y = 0; y < layer.rows; ++y) {
    Vec3f* out = layer.cells.data() + size_t(y) * size_t(layer.columns + 1);
    for (int x = 0; x < image.width(); ++x) {
      const Vec3f value = image.at(x, y);
      if (!stripes) {
        out[x] = value;
        continue;
      }
      for (int s = 0; s < 3; ++s)  // stripe s, left to right, passes one channel
        out[3 * x + s] = value * stripePasses(panel.subpixels, s);
    }
  }
  return layer;
}

// The diffuser (sim/diffuser.h): the rear layer's cells blurred, the zero cell that ends each
// row left dark.
void DisplaySimulator::blur(Layer& layer, double sigmaMm, int threads) {
  if (!(sigmaMm > 0)) return;
  diffuserBlur(layer.cells.data(), layer.columns, layer.rows, size_t(layer.columns + 1),
               sigmaMm / layer.cellWidthMm, sigmaMm / layer.cellHeightMm, threads);
}

DisplaySimulator::DisplaySimulator(const DisplayDesign& design, LayerImages layers,
                                   const SimulationOptions& options)
    : design_(design), options_(options) {
  const DisplaySpec& spec = design.spec;
  checkSize(design, layers.image, spec.imagePanel, "/image_layer", "image");
  checkSize(design, layers.mask, spec.maskPanel, "/mask_layer", "mask");
  checkOptions(options);
  threads_ = workerCount(options.threads);

  double sum = 0;
  for (const Vec3f& p : layers.mask.pixels()) sum += (double(p.x) + p.y + p.z) / 3.0;
  maskMean_ = sum / double(layers.mask.pixels().size());

  const bool imageInFront = spec.order == LayerOrder::BarrierBack;
  const Panel& frontPanel = imageInFront ? spec.imagePanel : spec.maskPanel;
  const Panel& rearPanel = imageInFront ? spec.maskPanel : spec.imagePanel;
  front_ = makeLayer(imageInFront ? layers.image : layers.mask, frontPanel, options.colourFilters);
  rear_ = makeLayer(imageInFront ? layers.mask : layers.image, rearPanel, options.colourFilters);
  blur(rear_, options.diffuserSigmaMm, threads_);

  width_ = options.width > 0 ? options.width : frontPanel.width;
  height_ = options.height > 0 ? options.height : frontPanel.height;

  double normaliser = 1.0;
  if (options.normalise) {
    // A stripe passes one channel of three: a filtered layer's mean throughput is 1/3.
    for (const Layer* layer : {&front_, &rear_})
      if (layer->striped) normaliser *= 3.0;
    if (options.normalisation > 0)
      normaliser /= options.normalisation;
    else if (maskMean_ > 0)
      normaliser /= maskMean_;  // a black mask has nothing to normalise
  }
  scale_ = normaliser / double(pupilPoints({}).size());

  viewsThroughSeenLayers_ = options.samplesPerPixel == 0 && width_ == frontPanel.width &&
                            height_ == frontPanel.height &&
                            design.spec.mask.kind != MaskKind::Pinholes;
  // SeenLayers averages the pupil's sights itself.
  seenScale_ = normaliser;
  if (viewsThroughSeenLayers_ && front_.striped) {
    // SeenLayers passes the front layer's pixels through their stripes itself, and undoes their
    // 1/3.
    frontPixels_ = imageInFront ? std::move(layers.image) : std::move(layers.mask);
    seenScale_ = normaliser / 3.0;
  }
}

Image DisplaySimulator::seen(const Vec3d& eye) const {
  if (!viewsThroughSeenLayers()) return atDisplayResolution(design_, view(eye));
  checkEye(eye);
  // The rear cells as they are (striped, blurred), each row read up to its dark end cell.
  const LayerRows rear(rear_.cells.data(), size_t(rear_.columns + 1), rear_.columns, rear_.rows);
  const SeenOptics optics{.colourFilters = options_.colourFilters,
                          .rearStripeCells = rear_.striped,
                          .pupilDiameterMm = options_.pupilDiameterMm,
                          .pupilSamples = options_.pupilSamples};
  Image out;
  if (front_.striped) {
    // The front layer's pixels through SeenLayers' stripes.
    out = SeenLayers(design_, eye, optics).view(frontPixels_, rear, options_.threads);
  } else {
    const LayerRows front(front_.cells.data(), size_t(front_.columns + 1), front_.columns,
                          front_.rows);
    out = SeenLayers(design_, eye, optics).view(front, rear, options_.threads);
  }
  const Vec3f scale = options_.backlight * float(seenScale_);
  forRows(out.height(), threads_, [&](int begin, int end) {
    for (int y = begin; y < end; ++y)
      for (int x = 0; x < out.width(); ++x) out.at(x, y) = out.at(x, y) * scale;
  });
  return out;
}

std::vector<Vec3d> DisplaySimulator::pupilPoints(const Vec3d& eye) const {
  return parallax::pupilPoints(eye, options_.pupilDiameterMm, options_.pupilSamples);
}

Image DisplaySimulator::view(const Vec3d& eye) const {
  checkEye(eye);
  const int n = int(std::lround(std::sqrt(double(options_.samplesPerPixel))));
  const std::vector<Vec3d> eyes = pupilPoints(eye);
  const size_t pupil = eyes.size();

  // The eye's line through a front point F meets the rear layer where x depends on F.x alone
  // and y on F.y alone, so an output pixel's light is a sum over its pieces along x times its
  // pieces along y (piecesAlongAxis), the same for every row and column, once per pupil point.
  const double frontWidth = front_.columns * front_.cellWidthMm;
  const double frontHeight = front_.rows * front_.cellHeightMm;
  const double rearWidth = rear_.columns * rear_.cellWidthMm;
  const double rearHeight = rear_.rows * rear_.cellHeightMm;
  std::vector<std::vector<Piece>> across(pupil), down(pupil);
  std::vector<std::vector<uint32_t>> acrossStart(pupil), downStart(pupil);
  for (size_t p = 0; p < pupil; ++p) {
    const Vec3d& e = eyes[p];
    const double stretch = (e.z + design_.gapMm) / e.z;
    // x across the front layer: frontX = (t - 1/2) frontWidth; rearX = e.x + (frontX - e.x)
    // stretch; rear column coordinate (rearX + rearWidth / 2) / cell width.
    const auto column = [&](double t) {
      const double rearX = e.x + ((t - 0.5) * frontWidth - e.x) * stretch;
      return (rearX + 0.5 * rearWidth) / rear_.cellWidthMm;
    };
    piecesAlongAxis(width_, front_.columns, rear_.columns, column(0), column(1) - column(0), n,
                    rear_.columns, across[p], acrossStart[p]);
    // y down the front layer: frontY = (1/2 - t) frontHeight; rear row coordinate from the top.
    const auto row = [&](double t) {
      const double rearY = e.y + ((0.5 - t) * frontHeight - e.y) * stretch;
      return (0.5 * rearHeight - rearY) / rear_.cellHeightMm;
    };
    piecesAlongAxis(height_, front_.rows, rear_.rows, row(0), row(1) - row(0), n, -1, down[p],
                    downStart[p]);
  }

  Image out(width_, height_);
  const Vec3f scale = options_.backlight * float(scale_);
  forRows(height_, threads_, [&](int begin, int end) {
    std::vector<Vec3f> sum(static_cast<size_t>(width_));
    for (int j = begin; j < end; ++j) {
      std::fill(sum.begin(), sum.end(), Vec3f(0.0f));
      for (size_t p = 0; p < pupil; ++p)
        for (uint32_t k = downStart[p][size_t(j)]; k < downStart[p][size_t(j) + 1]; ++k) {
          const Piece& vertical = down[p][k];
          if (vertical.rear < 0) continue;  // above or below the rear panel: dark
          const Vec3f* front = front_.row(vertical.front);
          const Vec3f* rear = rear_.row(vertical.rear);
          const Piece* piece = across[p].data();
          const uint32_t* starts = acrossStart[p].data();
          for (int i = 0; i < width_; ++i) {
            Vec3f light(0.0f);
            for (uint32_t a = starts[i]; a < starts[i + 1]; ++a)
              light += front[piece[a].front] * rear[piece[a].rear] * piece[a].weight;
            sum[size_t(i)] += light * vertical.weight;
          }
        }
      for (int i = 0; i < width_; ++i) out.at(i, j) = sum[size_t(i)] * scale;
    }
  });
  return out;
}

Image atDisplayResolution(const DisplayDesign& d, const Image& image) {
  const double periodPx = d.screenPeriodMm / (d.frontWidthMm() / double(image.width()));
  Image out = boxFilterX(image, periodPx);
  if (d.spec.mask.kind == MaskKind::Pinholes) {
    const double rowPeriodMm = d.spec.mask.verticalPeriodPx * d.spec.maskPanel.pitchMm *
                               (d.viewDistanceMm - d.imageLayerZ()) /
                               (d.viewDistanceMm - d.maskLayerZ());
    out = boxFilterY(out, rowPeriodMm / (d.frontHeightMm() / double(image.height())));
  }
  return out;
}

}  // namespace parallax
