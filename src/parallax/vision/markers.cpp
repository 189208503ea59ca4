// ArUco markers through OpenCV. ArUco moved from the contrib module `aruco` (OpenCV 4.6, Debian
// 12: free functions taking Ptr<Dictionary>) into objdetect in 4.7 (4.10, Debian 13: the
// ArucoDetector class); src/parallax/vision/CMakeLists.txt links the one that the version says,
// and the same version test picks the API here.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/version.hpp>
#include <opencv2/imgproc.hpp>
#if CV_VERSION_MAJOR > 4 || (CV_VERSION_MAJOR == 4 && CV_VERSION_MINOR >= 7)
#define PARALLAX_ARUCO_IN_OBJDETECT 1
#include <opencv2/objdetect/aruco_detector.hpp>
#else
#define PARALLAX_ARUCO_IN_OBJDETECT 0
#include <opencv2/aruco.hpp>
#endif

#include "parallax/vision/vision.h"

namespace parallax::vision {
namespace {

#if PARALLAX_ARUCO_IN_OBJDETECT
const cv::aruco::Dictionary& dictionary() {
  static const cv::aruco::Dictionary d =
      cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_250);
  return d;
}
int dictionaryMarkers() {
  return dictionary().bytesList.rows;
}
#else
const cv::Ptr<cv::aruco::Dictionary>& dictionary() {
  static const cv::Ptr<cv::aruco::Dictionary> d =
      cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_250);
  return d;
}
int dictionaryMarkers() {
  return dictionary()->bytesList.rows;
}
#endif

// One pixel per cell, the one-cell border included.
cv::Mat drawMarker(int id) {
  cv::Mat cells;
#if PARALLAX_ARUCO_IN_OBJDETECT
  cv::aruco::generateImageMarker(dictionary(), id, kMarkerCells, cells, 1);
#else
  cv::aruco::drawMarker(dictionary(), id, kMarkerCells, cells, 1);
#endif
  return cells;
}

// OpenCV's subpixel corners (cornerSubPix on the grey photo), iterated further than its defaults
// (30 iterations, 0.1 px): where refineBySides starts.
template <typename Parameters>
void refineCorners(Parameters& p) {
  p.cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  p.cornerRefinementMaxIterations = 100;
  p.cornerRefinementMinAccuracy = 0.01;
}

void detect(const cv::Mat& grey, std::vector<std::vector<cv::Point2f>>& corners,
            std::vector<int>& ids) {
#if PARALLAX_ARUCO_IN_OBJDETECT
  cv::aruco::DetectorParameters parameters;
  refineCorners(parameters);
  const cv::aruco::ArucoDetector detector(dictionary(), parameters);
  detector.detectMarkers(grey, corners, ids);
#else
  const cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  refineCorners(*parameters);
  cv::aruco::detectMarkers(grey, dictionary(), corners, ids, parameters);
#endif
}

// The grey level at (x, y) in OpenCV's convention, bilinear; false outside the picture.
bool greyAt(const cv::Mat& grey, double x, double y, double& value) {
  if (!(x >= 0 && y >= 0 && x <= grey.cols - 1 && y <= grey.rows - 1)) return false;
  const int x0 = std::min(int(x), std::max(grey.cols - 2, 0));
  const int y0 = std::min(int(y), std::max(grey.rows - 2, 0));
  const int x1 = std::min(x0 + 1, grey.cols - 1), y1 = std::min(y0 + 1, grey.rows - 1);
  const double fx = x - x0, fy = y - y0;
  const auto at = [&](int yy, int xx) { return double(grey.at<uint8_t>(yy, xx)); };
  value = (1 - fy) * ((1 - fx) * at(y0, x0) + fx * at(y0, x1)) +
          fy * ((1 - fx) * at(y1, x0) + fx * at(y1, x1));
  return true;
}

struct Line {
  cv::Point2d point, direction;  // direction of unit length
};

// The straight edge between the marker's black border and the white around it, near the side
// from a to b: where the grey level crosses halfway between the two, across the side at many
// points away from the corners, and a line fitted through those points (total least squares).
std::optional<Line> fitSide(const cv::Mat& grey, cv::Point2d a, cv::Point2d b, cv::Point2d centre) {
  const double length = cv::norm(b - a);
  if (length < 6) return std::nullopt;
  const cv::Point2d along = (b - a) / length;
  cv::Point2d out(-along.y, along.x);
  if (out.dot((a + b) * 0.5 - centre) < 0) out = -out;
  // Within the border (one cell of the marker's six) on the inside, and within as much of the
  // white margin that the detector required on the outside.
  const double reach = std::clamp(0.45 * length / kMarkerCells, 1.5, 6.0), step = 0.25;
  const int steps = int(2 * reach / step);
  std::vector<cv::Point2d> edge;
  std::vector<double> profile(size_t(steps) + 1);
  const int count = std::max(8, int(0.6 * length));
  for (int i = 0; i < count; ++i) {
    const cv::Point2d middle = a + (b - a) * (0.2 + 0.6 * (i + 0.5) / count);
    bool inside = true;
    for (int k = 0; k <= steps && inside; ++k) {
      const cv::Point2d p = middle + out * (-reach + k * step);
      inside = greyAt(grey, p.x, p.y, profile[size_t(k)]);
    }
    if (!inside) continue;
    const auto [dark, bright] = std::minmax_element(profile.begin(), profile.end());
    if (*bright - *dark < 16) continue;  // no edge here
    const double half = (*dark + *bright) / 2;
    // The crossing from dark to bright nearest the side's line.
    double best = 1e9;
    for (int k = 0; k < steps; ++k) {
      const double v0 = profile[size_t(k)], v1 = profile[size_t(k + 1)];
      if (v0 < half && v1 >= half) {
        const double s = -reach + step * (k + (half - v0) / (v1 - v0));
        if (std::abs(s) < std::abs(best)) best = s;
      }
    }
    if (best < 1e9) edge.push_back(middle + out * best);
  }
  if (edge.size() < 5) return std::nullopt;
  cv::Point2d mean(0, 0);
  for (const cv::Point2d& p : edge) mean += p;
  mean /= double(edge.size());
  double sxx = 0, sxy = 0, syy = 0;
  for (const cv::Point2d& p : edge) {
    const cv::Point2d d = p - mean;
    sxx += d.x * d.x, sxy += d.x * d.y, syy += d.y * d.y;
  }
  const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);  // the principal direction
  return Line{mean, {std::cos(angle), std::sin(angle)}};
}

std::optional<cv::Point2d> intersect(const Line& l, const Line& m) {
  const double det = l.direction.x * m.direction.y - l.direction.y * m.direction.x;
  if (std::abs(det) < 0.1) return std::nullopt;  // nearly parallel: no reliable corner
  const cv::Point2d d = m.point - l.point;
  return l.point + l.direction * ((d.x * m.direction.y - d.y * m.direction.x) / det);
}

// cornerSubPix finds where the gradients around a point are orthogonal to it, which on the
// convex corner of a blurred square lies a few tenths of a pixel inside it; the marker's sides
// are straight (a plane seen through a pinhole, lens distortion aside over so short a length),
// so their intersections are the corners. Twice: the second pass centres the profiles across
// each side on the first pass's lines. A corner that fails or moves too far stays OpenCV's.
void refineBySides(const cv::Mat& grey, std::vector<cv::Point2f>& corners) {
  std::array<cv::Point2d, 4> c;
  for (size_t k = 0; k < 4; ++k) c[k] = corners[k];
  const cv::Point2d centre = (c[0] + c[1] + c[2] + c[3]) * 0.25;
  const double cell = (cv::norm(c[1] - c[0]) + cv::norm(c[2] - c[1]) + cv::norm(c[3] - c[2]) +
                       cv::norm(c[0] - c[3])) /
                      (4 * kMarkerCells);
  for (int pass = 0; pass < 2; ++pass) {
    std::array<std::optional<Line>, 4> sides;
    for (size_t k = 0; k < 4; ++k) sides[k] = fitSide(grey, c[k], c[(k + 1) % 4], centre);
    std::array<cv::Point2d, 4> next = c;
    for (size_t k = 0; k < 4; ++k) {
      const std::optional<Line>& before = sides[(k + 3) % 4];
      if (!before || !sides[k]) continue;
      const std::optional<cv::Point2d> corner = intersect(*before, *sides[k]);
      if (corner && cv::norm(*corner - cv::Point2d(corners[k])) < std::max(1.0, 0.25 * cell))
        next[k] = *corner;
    }
    c = next;
  }
  for (size_t k = 0; k < 4; ++k) corners[k] = cv::Point2f(float(c[k].x), float(c[k].y));
}

}  // namespace

int markerDictionarySize() {
  return dictionaryMarkers();
}

std::vector<uint8_t> markerCells(int id) {
  if (id < 0 || id >= markerDictionarySize())
    throw std::out_of_range("markerCells: no marker " + std::to_string(id));
  const cv::Mat drawn = drawMarker(id);
  std::vector<uint8_t> cells(kMarkerCells * kMarkerCells);
  for (int r = 0; r < kMarkerCells; ++r)
    for (int c = 0; c < kMarkerCells; ++c)
      cells[size_t(r * kMarkerCells + c)] = drawn.at<uint8_t>(r, c) > 127 ? 1 : 0;
  return cells;
}

std::vector<DetectedMarker> detectMarkers(const Photo& photo) {
  if (photo.width <= 0 || photo.height <= 0 ||
      photo.rgb.size() != size_t(photo.width) * size_t(photo.height) * 3)
    throw std::invalid_argument("detectMarkers: a photo without pixels or of the wrong size");
  // Rec. 601 luma, as OpenCV's RGB2GRAY (no imgproc needed for it).
  cv::Mat grey(photo.height, photo.width, CV_8U);
  const uint8_t* in = photo.rgb.data();
  for (int y = 0; y < photo.height; ++y) {
    uint8_t* out = grey.ptr<uint8_t>(y);
    for (int x = 0; x < photo.width; ++x, in += 3)
      out[x] = uint8_t((299 * in[0] + 587 * in[1] + 114 * in[2] + 500) / 1000);
  }
  // At the photo's own size and at a half and a quarter of it (area-averaged): a photo of a
  // screen close up resolves the panel's pixels, their black matrix and colour stripes, and the
  // detector's thresholds see stripes in every white cell; averaged down, the cells are flat
  // again. A marker found at several sizes is taken from the finest.
  std::vector<DetectedMarker> markers;
  std::vector<char> found(size_t(markerDictionarySize()), 0);
  cv::Mat level = grey;
  for (double scale = 1.0; scale >= 0.25 && std::min(level.cols, level.rows) >= 64; scale /= 2) {
    if (scale < 1.0) cv::resize(grey, level, cv::Size(), scale, scale, cv::INTER_AREA);
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    detect(level, corners, ids);
    for (size_t i = 0; i < ids.size(); ++i) {
      if (ids[i] < 0 || ids[i] >= markerDictionarySize() || found[size_t(ids[i])]) continue;
      found[size_t(ids[i])] = 1;
      refineBySides(level, corners[i]);
      DetectedMarker marker;
      marker.id = ids[i];
      // OpenCV's pixel (i, j) is centred at (i, j); ours at (i + 0.5, j + 0.5); a pixel of the
      // level spans 1 / scale of the photo's.
      for (size_t k = 0; k < 4; ++k)
        marker.corners[k] = {(corners[i][k].x + 0.5) / scale, (corners[i][k].y + 0.5) / scale};
      markers.push_back(marker);
    }
  }
  std::stable_sort(markers.begin(), markers.end(),
                   [](const DetectedMarker& a, const DetectedMarker& b) { return a.id < b.id; });
  return markers;
}

}  // namespace parallax::vision
