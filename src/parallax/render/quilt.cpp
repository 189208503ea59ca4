#include "parallax/render/quilt.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <stdexcept>

#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/core/parallel.h"
#include "parallax/display/display_model.h"
#include "parallax/display/mask.h"
#include "parallax/render/display_render.h"

namespace parallax {

namespace {

constexpr int kMaxTilesPerSide = 1024;
constexpr const char* kNameConvention =
    "expected the name to end in _qs<columns>x<rows>a<aspect> before the extension, e.g. "
    "scene_qs5x9a1.7778.png";

bool parseCount(std::string_view text, int& count) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, count);
  return error == std::errc() && stop == end && count >= 1 && count <= kMaxTilesPerSide;
}

}  // namespace

bool parseColumnsByRows(std::string_view text, int& columns, int& rows) {
  const size_t x = text.find('x');
  if (x == std::string_view::npos) return false;
  int c = 0, r = 0;
  if (!parseCount(text.substr(0, x), c) || !parseCount(text.substr(x + 1), r)) return false;
  columns = c;
  rows = r;
  return true;
}

QuiltLayout parseQuiltName(const std::string& path) {
  const std::string stem = std::filesystem::path(path).stem().string();
  const size_t at = stem.rfind("_qs");
  if (at == std::string::npos)
    throw InputError(path, "", "no quilt layout: " + std::string(kNameConvention));
  const std::string ending = stem.substr(at);
  // The whole ending, to the extension: _qs, columns, x, rows, then optionally a and a positive
  // decimal number (digits, optionally a point and more digits).
  const size_t a = ending.find('a', 3);
  const std::string counts = ending.substr(3, a == std::string::npos ? std::string::npos : a - 3);
  QuiltLayout layout;
  if (a == std::string::npos) {  // _qs8x6: the aspect left to the display, as Looking Glass does
    if (!parseColumnsByRows(counts, layout.columns, layout.rows))
      throw InputError(path, "", "malformed quilt layout '" + ending + "': " + kNameConvention);
    return layout;
  }
  const std::string aspect = ending.substr(a + 1);
  const size_t point = aspect.find('.');
  const auto digits = [](const std::string& t) {
    return !t.empty() && t.find_first_not_of("0123456789") == std::string::npos;
  };
  const bool aspectOk = point == std::string::npos
                            ? digits(aspect)
                            : digits(aspect.substr(0, point)) && digits(aspect.substr(point + 1));
  if (!aspectOk || !parseColumnsByRows(counts, layout.columns, layout.rows))
    throw InputError(path, "", "malformed quilt layout '" + ending + "': " + kNameConvention);
  // strtod, not stod: a long run of digits overflows (or underflows) to a value we refuse
  // below instead of throwing std::out_of_range (a fuzzing finding, fuzz/regressions).
  layout.aspect = std::strtod(aspect.c_str(), nullptr);
  if (!(layout.aspect >= 1e-3 && layout.aspect <= 1e3))
    throw InputError(path, "", "quilt aspect must be between 0.001 and 1000, got '" + aspect + "'");
  return layout;
}

std::string formatQuiltAspect(double aspect) {
  char text[64];
  std::snprintf(text, sizeof text, "%.4f", aspect);
  std::string s = text;
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s;
}

std::string quiltFileName(const std::string& stem, const QuiltLayout& layout,
                          const std::string& extension) {
  // No aspect known: no `a` ending (the display's, as when Looking Glass leaves it out).
  std::string name =
      stem + "_qs" + std::to_string(layout.columns) + "x" + std::to_string(layout.rows);
  if (layout.aspect > 0) name += 'a' + formatQuiltAspect(layout.aspect);
  return name + extension;
}

std::string quiltVideoPath(const std::string& path, const QuiltLayout& layout) {
  const std::filesystem::path p(path);
  const std::string stem = p.stem().string();
  if (stem.rfind("_qs") != std::string::npos) {
    QuiltLayout named;
    try {
      named = parseQuiltName(path);
    } catch (const InputError&) {
      return quiltFileName((p.parent_path() / stem).string(), layout, p.extension().string());
    }
    const bool same = named.columns == layout.columns && named.rows == layout.rows &&
                      (named.aspect == 0 || std::abs(named.aspect / layout.aspect - 1.0) < 0.005);
    if (!same)
      throw std::invalid_argument("the name says a " + std::to_string(named.columns) + "x" +
                                  std::to_string(named.rows) + " quilt" +
                                  (named.aspect > 0 ? " a" + formatQuiltAspect(named.aspect) : "") +
                                  ", the render makes " + quiltFileName("", layout, "").substr(1) +
                                  ": leave the _qs ending out, parallax adds it");
    if (named.aspect > 0) return path;
    // _qs7x7 without the aspect: completed, so that Looking Glass Studio reads the display's.
    const std::string bare = stem.substr(0, stem.rfind("_qs"));
    return quiltFileName((p.parent_path() / bare).string(), layout, p.extension().string());
  }
  return quiltFileName((p.parent_path() / stem).string(), layout, p.extension().string());
}

Image assembleQuilt(const std::vector<Image>& views, int columns, int rows) {
  if (columns < 1 || rows < 1 || views.size() != size_t(columns) * size_t(rows))
    throw std::invalid_argument("assembleQuilt: need columns * rows views");
  const int w = views[0].width(), h = views[0].height();
  Image quilt(columns * w, rows * h);
  for (int k = 0; k < int(views.size()); ++k) {
    if (views[size_t(k)].width() != w || views[size_t(k)].height() != h)
      throw std::invalid_argument("assembleQuilt: views differ in size");
    // Row k / columns counted from the bottom; image rows are counted from the top.
    const int left = (k % columns) * w, top = (rows - 1 - k / columns) * h;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) quilt.at(left + x, top + y) = views[size_t(k)].at(x, y);
  }
  return quilt;
}

std::vector<Image> splitQuilt(const Image& quilt, const QuiltLayout& layout,
                              const std::string& source) {
  const int w = quilt.width() / layout.columns, h = quilt.height() / layout.rows;
  const std::string size = std::to_string(quilt.width()) + "x" + std::to_string(quilt.height());
  const std::string grid = std::to_string(layout.columns) + "x" + std::to_string(layout.rows);
  if (w < 1 || h < 1)
    throw InputError(source, "", size + " pixels are too few for " + grid + " tiles");
  std::vector<Image> views;
  for (int k = 0; k < layout.views(); ++k) {
    const int left = (k % layout.columns) * w;
    const int top = quilt.height() - (k / layout.columns + 1) * h;
    Image view(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) view.at(x, y) = quilt.at(left + x, top + y);
    views.push_back(std::move(view));
  }
  return views;
}

int interlacedViewCount(const DisplayDesign& design) {
  return interleavedViewCount(design);
}

std::vector<int> designViewsLeftToRight(const DisplayDesign& design) {
  const std::unique_ptr<DisplayModel> display = makeBarrierDisplay(design);
  std::vector<int> order(size_t(interlacedViewCount(design)));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&display](int a, int b) {
    return display->viewPosition(a).x < display->viewPosition(b).x;
  });
  return order;
}

Image interlaceCameraViews(const DisplayDesign& design, const std::vector<Image>& cameraViews) {
  const std::vector<int> designView = designViewsLeftToRight(design);
  if (cameraViews.size() != designView.size())
    throw std::invalid_argument("interlaceCameraViews: the display needs " +
                                std::to_string(designView.size()) + " views");
  const Panel& panel = design.spec.imagePanel;
  std::vector<Image> views(designView.size());
  for (size_t k = 0; k < cameraViews.size(); ++k) {
    const Image& view = cameraViews[k];
    const bool fits = view.width() == panel.width && view.height() == panel.height;
    views[size_t(designView[k])] = fits ? view : resizeArea(view, panel.width, panel.height);
  }
  return interleaveViews(design, views);
}

Vec3d quiltEyePosition(const DisplayDesign& design, int camera, int count) {
  const double S = design.viewZoneWidthMm;
  return {design.spec.viewZoneCenterXMm + S * ((camera + 0.5) / count - 0.5),
          design.spec.viewZoneHeightMm, design.viewDistanceMm};
}

std::vector<Image> renderQuiltViews(const Scene& scene, const Accelerator& accelerator,
                                    const DisplayDesign& design, const RenderSettings& settings,
                                    int count, int width, int height, RenderStats* stats,
                                    const ProgressCallback& progress) {
  const bool horizontalOnly = !MaskGeometry(design).isPinholeGrid();
  std::vector<Image> views;
  RenderStats total;
  for (int k = 0; k < count; ++k) {
    const WindowCamera camera(quiltEyePosition(design, k, count), design, scene.display, width,
                              height, horizontalOnly);
    RenderStats one;
    views.push_back(render(scene, accelerator, camera, settings, &one, [&](int done, int tiles) {
      if (progress) progress(k * tiles + done, count * tiles);
    }));
    total += one;
  }
  if (stats) *stats = total;
  return views;
}

Vec3d quiltEyePosition(const DisplayModel& display, int camera, int count) {
  return display.eyeAcrossZone((camera + 0.5) / count);
}

void renderQuiltTiles(const Scene& scene, const Accelerator& accelerator,
                      const DisplayModel& display, const RenderSettings& settings,
                      const QuiltLayout& layout, int tileWidth, int tileHeight,
                      const QuiltTileSink& sink, RenderStats* stats,
                      const ProgressCallback& progress) {
  const int count = layout.views();
  RenderStats total;
  for (int k = 0; k < count; ++k) {
    const WindowCamera camera(quiltEyePosition(display, k, count), display, scene.display,
                              tileWidth, tileHeight, display.horizontalParallaxOnly());
    RenderStats one;
    const Image view = render(scene, accelerator, camera, settings, &one, [&](int done, int n) {
      if (progress) progress(k * n + done, count * n);
    });
    // View k is tile (k mod columns, k div columns) counted from the bottom-left.
    sink(k, (k % layout.columns) * tileWidth, (layout.rows - 1 - k / layout.columns) * tileHeight,
         view);
    total += one;
  }
  if (stats) *stats = total;
}

Image renderQuilt(const Scene& scene, const Accelerator& accelerator, const DisplayModel& display,
                  const RenderSettings& settings, const QuiltLayout& layout, int tileWidth,
                  int tileHeight, RenderStats* stats, const ProgressCallback& progress) {
  Image quilt(layout.columns * tileWidth, layout.rows * tileHeight);
  renderQuiltTiles(
      scene, accelerator, display, settings, layout, tileWidth, tileHeight,
      [&](int, int left, int top, const Image& view) {
        for (int y = 0; y < tileHeight; ++y)
          for (int x = 0; x < tileWidth; ++x) quilt.at(left + x, top + y) = view.at(x, y);
      },
      stats, progress);
  return quilt;
}

namespace {

// Bilinear lookup of channel c at continuous image position (x, y) (pixel centres at +0.5),
// clamped to the image.
float bilinear(const Image& image, double x, double y, int c) {
  const double fx = std::clamp(x - 0.5, 0.0, image.width() - 1.0);
  const double fy = std::clamp(y - 0.5, 0.0, image.height() - 1.0);
  const int x0 = int(fx), y0 = int(fy);
  const int x1 = std::min(x0 + 1, image.width() - 1), y1 = std::min(y0 + 1, image.height() - 1);
  const double tx = fx - x0, ty = fy - y0;
  const double top = image.at(x0, y0)[c] * (1 - tx) + image.at(x1, y0)[c] * tx;
  const double bottom = image.at(x0, y1)[c] * (1 - tx) + image.at(x1, y1)[c] * tx;
  return float(top * (1 - ty) + bottom * ty);
}

}  // namespace

namespace {

// The two views of N that subpixel (x, y, c) blends, (1 - t) below + t above.
struct ViewBlend {
  int below, above;
  double t;
};
ViewBlend subpixelViewBlend(const LenticularDesign& design, int x, int y, int c, int n,
                            ViewResampling resampling) {
  // The quilt camera on the design line that the subpixel's light reaches (the optics: view
  // f's own with bundles converging at D); camera i covers [i / N, (i + 1) / N).
  const double panelX = subpixelPointMm(design, x + 0.5, y + 0.5, c).x;
  const double position =
      lensQuiltFraction(design, panelX, viewFraction(design, x, y, c)) * n - 0.5;
  const int below = std::clamp(int(std::floor(position)), 0, n - 1);
  const int above = std::clamp(below + 1, 0, n - 1);
  const double t = std::clamp(position - std::floor(position), 0.0, 1.0);
  // Beyond the first and last view: the nearest of them.
  if (position < 0) return {below, above, 0.0};
  if (position > n - 1) return {below, above, 1.0};
  // Nearest: the view whose centre is nearer, floor(f N) (t = 1/2 rounds up, as floor does).
  if (resampling == ViewResampling::Nearest) return {below, above, t < 0.5 ? 0.0 : 1.0};
  return {below, above, t};
}

}  // namespace

Image interlaceQuiltLenticular(const LenticularDesign& design, const std::vector<Image>& views,
                               ViewResampling resampling) {
  if (views.empty()) throw std::invalid_argument("interlaceQuiltLenticular: no views");
  const int w = design.calibration.screenW, h = design.calibration.screenH;
  const int n = int(views.size());
  const double sx = double(views[0].width()) / w, sy = double(views[0].height()) / h;
  Image panel(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const ViewBlend blend = subpixelViewBlend(design, x, y, c, n, resampling);
        const double px = (x + 0.5) * sx, py = (y + 0.5) * sy;
        const double a = bilinear(views[size_t(blend.below)], px, py, c);
        const double b = bilinear(views[size_t(blend.above)], px, py, c);
        panel.at(x, y)[c] = float(blend.t == 0   ? a
                                  : blend.t == 1 ? b
                                                 : a * (1 - blend.t) + b * blend.t);
      }
  return panel;
}

QuiltInterlacer::QuiltInterlacer(const LenticularDesign& design, const QuiltLayout& layout,
                                 int quiltWidth, int quiltHeight, ViewResampling resampling)
    : panelWidth_(design.calibration.screenW),
      panelHeight_(design.calibration.screenH),
      quiltWidth_(quiltWidth) {
  const int tileW = quiltWidth / layout.columns, tileH = quiltHeight / layout.rows;
  const int n = layout.views();
  if (tileW < 1 || tileH < 1 || n < 1 || n > 65535)
    throw std::invalid_argument("QuiltInterlacer: no tiles in the quilt");
  for (int k = 0; k < n; ++k) {  // splitQuilt's tiles: view 0 at the bottom left
    const int64_t left = (k % layout.columns) * tileW;
    const int64_t top = quiltHeight - (k / layout.columns + 1) * tileH;
    tileOrigin_.push_back(top * quiltWidth + left);
  }
  const double sx = double(tileW) / panelWidth_, sy = double(tileH) / panelHeight_;
  taps_.resize(size_t(panelWidth_) * size_t(panelHeight_));
  views_.resize(taps_.size() * 3);
  parallelFor(panelHeight_, 0, 8, [&](int64_t begin, int64_t end) {
    for (int y = int(begin); y < int(end); ++y)
      for (int x = 0; x < panelWidth_; ++x) {
        // bilinear()'s taps at the pixel's place in a tile.
        const size_t i = size_t(y) * size_t(panelWidth_) + size_t(x);
        const double fx = std::clamp((x + 0.5) * sx - 0.5, 0.0, tileW - 1.0);
        const double fy = std::clamp((y + 0.5) * sy - 0.5, 0.0, tileH - 1.0);
        const int x0 = int(fx), y0 = int(fy);
        const int x1 = std::min(x0 + 1, tileW - 1), y1 = std::min(y0 + 1, tileH - 1);
        taps_[i] = {y0 * quiltWidth + x0, x1 - x0, (y1 - y0) * quiltWidth, float(fx - x0),
                    float(fy - y0)};
        for (int c = 0; c < 3; ++c) {
          const ViewBlend blend = subpixelViewBlend(design, x, y, c, n, resampling);
          views_[3 * i + size_t(c)] = {uint16_t(blend.below), uint16_t(blend.above),
                                       float(blend.t)};
        }
      }
  });
}

double QuiltInterlacer::bytesPerPanelPixel() {
  return sizeof(PixelTaps) + 3 * sizeof(SubpixelViews);
}

void QuiltInterlacer::interlace(const uint8_t* quilt, uint8_t* panel, int threads) const {
  static const std::array<float, 256> decode = [] {
    std::array<float, 256> table{};
    for (int k = 0; k < 256; ++k) table[size_t(k)] = srgb8ToLinear(uint8_t(k));
    return table;
  }();
  parallelFor(panelHeight_, threads, 16, [&](int64_t begin, int64_t end) {
    std::vector<float> row(size_t(panelWidth_) * 3);
    for (int64_t y = begin; y < end; ++y) {
      const size_t first = size_t(y) * size_t(panelWidth_);
      for (int x = 0; x < panelWidth_; ++x) {
        const PixelTaps& p = taps_[first + size_t(x)];
        for (int c = 0; c < 3; ++c) {
          const SubpixelViews& v = views_[3 * (first + size_t(x)) + size_t(c)];
          const auto sample = [&](int view) {
            const uint8_t* q = quilt + 3 * (tileOrigin_[view] + p.offset) + c;
            const float top = decode[q[0]] * (1 - p.tx) + decode[q[3 * p.right]] * p.tx;
            const float bottom =
                decode[q[3 * p.down]] * (1 - p.tx) + decode[q[3 * (p.down + p.right)]] * p.tx;
            return top * (1 - p.ty) + bottom * p.ty;
          };
          const float a = v.t == 1 ? 0.0f : sample(v.below);
          const float b = v.t == 0 ? 0.0f : sample(v.above);
          row[3 * size_t(x) + size_t(c)] = v.t == 0 ? a : v.t == 1 ? b : a * (1 - v.t) + b * v.t;
        }
      }
      linearToSrgb8(row.data(), row.size(), panel + 3 * first);
    }
  });
}

std::vector<Image> resampleViews(const std::vector<Image>& views, int count,
                                 ViewResampling resampling) {
  if (views.empty() || count < 1) throw std::invalid_argument("resampleViews: no views");
  const int m = int(views.size());
  std::vector<Image> out;
  for (int k = 0; k < count; ++k) {
    // Where view k's eye sits among the camera views' eyes (camera j at (j + 1/2) / m).
    const double position = (k + 0.5) / count * m - 0.5;
    if (resampling == ViewResampling::Nearest) {
      out.push_back(views[size_t(std::clamp(int(std::lround(position)), 0, m - 1))]);
      continue;
    }
    const int below = std::clamp(int(std::floor(position)), 0, m - 1);
    const int above = std::min(below + 1, m - 1);
    const float t = float(std::clamp(position - below, 0.0, 1.0));
    Image blended = views[size_t(below)];
    if (above != below && t > 0)
      for (size_t i = 0; i < blended.pixels().size(); ++i)
        blended.pixels()[i] =
            views[size_t(below)].pixels()[i] * (1 - t) + views[size_t(above)].pixels()[i] * t;
    out.push_back(std::move(blended));
  }
  return out;
}

}  // namespace parallax
