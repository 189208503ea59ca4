// The camera fit: OpenCV's calibrateCamera (Zhang's planar calibration, then Levenberg-Marquardt
// on every view at once) restricted to what a phone's camera needs and a few photos can pin
// down: one focal length (square pixels), k1 and k2, the principal point at the photo's centre.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "parallax/core/error.h"
#include "parallax/vision/vision.h"

namespace parallax::vision {
namespace {

std::string sizeText(PhotoSize s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height);
}

}  // namespace

std::array<double, 3> CameraPose::cameraCentre() const {
  const std::array<double, 9>& r = rotation;
  const std::array<double, 3>& t = translation;
  return {-(r[0] * t[0] + r[3] * t[1] + r[6] * t[2]), -(r[1] * t[0] + r[4] * t[1] + r[7] * t[2]),
          -(r[2] * t[0] + r[5] * t[1] + r[8] * t[2])};
}

CameraFit fitCamera(const std::vector<std::vector<PlaneCorrespondence>>& views,
                    const std::vector<std::string>& names, int width, int height) {
  return fitCamera(views, names, std::vector<PhotoSize>(views.size(), PhotoSize{width, height}));
}

CameraFit fitCamera(const std::vector<std::vector<PlaneCorrespondence>>& views,
                    const std::vector<std::string>& names, const std::vector<PhotoSize>& sizes) {
  const size_t n = views.size();
  if (n == 0 || names.size() != n || sizes.size() != n)
    throw std::invalid_argument("fitCamera: needs views, and a name and a size for each");
  const PhotoSize first = sizes[0];
  if (first.width <= 0 || first.height <= 0)
    throw std::invalid_argument("fitCamera: a photo size of no pixels");
  // The fit happens in the first view's orientation; a view of the other one is turned into it
  // (a quarter clockwise: its point (x', y') is at (height' - y', x') there).
  std::vector<bool> turned(n, false);
  for (size_t i = 0; i < n; ++i) {
    const PhotoSize s = sizes[i];
    if (s.width == first.height && s.height == first.width && s.width != s.height) {
      turned[i] = true;
    } else if (s.width != first.width || s.height != first.height) {
      throw InputError(names[i], "",
                       "a " + sizeText(s) + " photo, where " + names[0] + " is " + sizeText(first) +
                           ": all photos must come from one camera");
    }
    if (views[i].size() < 4)
      throw InputError(
          names[i], "",
          std::to_string(views[i].size()) + " points found, where placing the camera needs 4");
  }
  std::vector<std::vector<cv::Point3f>> object(n);
  std::vector<std::vector<cv::Point2f>> image(n);
  for (size_t i = 0; i < n; ++i) {
    for (const PlaneCorrespondence& c : views[i]) {
      object[i].emplace_back(float(c.xMm), float(c.yMm), 0.0f);
      double x = c.photo.x, y = c.photo.y;
      if (turned[i]) {
        const double turnedX = sizes[i].height - y;
        y = x;
        x = turnedX;
      }
      // OpenCV's pixel (i, j) is centred at (i, j); ours at (i + 0.5, j + 0.5).
      image[i].emplace_back(float(x - 0.5), float(y - 0.5));
    }
  }
  const cv::Size imageSize(first.width, first.height);
  const double cx = first.width / 2.0 - 0.5, cy = first.height / 2.0 - 0.5;  // OpenCV's centre
  // The first focal length from the views' homographies (Zhang's closed form); a view seen
  // square on tells nothing about it, so a nonsensical guess falls back to the photo's width
  // (a phone's main camera sees about 65 degrees across).
  const double longSide = std::max(first.width, first.height);
  double focal = longSide;
  cv::Mat_<double> camera;
  cv::Mat distortion = cv::Mat::zeros(5, 1, CV_64F);  // k1, k2, p1, p2, k3
  std::vector<cv::Mat> rvecs, tvecs;
  cv::Mat intrinsicSigmas, extrinsicSigmas, viewErrors;
  try {
    const cv::Mat guess = cv::initCameraMatrix2D(object, image, imageSize, 1.0);
    const double f = guess.at<double>(0, 0);
    if (std::isfinite(f) && f > 0.2 * longSide && f < 20 * longSide) focal = f;
    camera = (cv::Mat_<double>(3, 3) << focal, 0, cx, 0, focal, cy, 0, 0, 1);
    const int flags = cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_PRINCIPAL_POINT |
                      cv::CALIB_FIX_ASPECT_RATIO | cv::CALIB_ZERO_TANGENT_DIST | cv::CALIB_FIX_K3;
    const cv::TermCriteria stop(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-12);
    cv::calibrateCamera(object, image, imageSize, camera, distortion, rvecs, tvecs, intrinsicSigmas,
                        extrinsicSigmas, viewErrors, flags, stop);
  } catch (const cv::Exception& e) {
    // Degenerate views (collinear points, one point repeated) make OpenCV's solvers fail.
    throw InputError(names[0], "", "the camera fit failed (" + e.err + ")");
  }
  CameraFit fit;
  fit.intrinsics.focalPx = camera(0, 0);
  if (!std::isfinite(fit.intrinsics.focalPx) || fit.intrinsics.focalPx <= 0)
    throw InputError(names[0], "", "the camera fit failed (no positive focal length)");
  fit.intrinsics.cx = first.width / 2.0;
  fit.intrinsics.cy = first.height / 2.0;
  fit.intrinsics.k1 = distortion.at<double>(0);
  fit.intrinsics.k2 = distortion.at<double>(1);
  // With the aspect ratio fixed OpenCV moves fy and derives fx from it: fy's sigma is the one.
  fit.focalSigmaPx = std::max(intrinsicSigmas.at<double>(0), intrinsicSigmas.at<double>(1));
  for (size_t i = 0; i < n; ++i) {
    cv::Matx33d r;
    cv::Rodrigues(rvecs[i], r);
    const cv::Vec3d t(tvecs[i].at<double>(0), tvecs[i].at<double>(1), tvecs[i].at<double>(2));
    CameraPose pose;
    CameraIntrinsics own = fit.intrinsics;
    if (turned[i]) {
      // Turned back: this view's camera frame is the fitted one turned a quarter about its
      // axis, X' = Y and Y' = -X (its rows: the fitted one's second row, minus its first).
      r = cv::Matx33d(r(1, 0), r(1, 1), r(1, 2), -r(0, 0), -r(0, 1), -r(0, 2), r(2, 0), r(2, 1),
                      r(2, 2));
      pose.translation = {t[1], -t[0], t[2]};
      std::swap(own.cx, own.cy);
    } else {
      pose.translation = {t[0], t[1], t[2]};
    }
    for (int k = 0; k < 9; ++k) pose.rotation[size_t(k)] = r(k / 3, k % 3);
    fit.poses.push_back(pose);
    fit.viewIntrinsics.push_back(own);
    fit.rmsErrorPx.push_back(viewErrors.at<double>(int(i)));
  }
  return fit;
}

PhotoPoint projectPoint(const CameraIntrinsics& intrinsics, const CameraPose& pose,
                        const std::array<double, 3>& pointMm) {
  // cv::projectPoints without tangential or higher terms, in our pixel convention: the
  // principal point is already ours (centre at width / 2), so nothing is shifted.
  const std::array<double, 9>& r = pose.rotation;
  const std::array<double, 3>& p = pointMm;
  const double x = r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + pose.translation[0];
  const double y = r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + pose.translation[1];
  const double z = r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + pose.translation[2];
  const double inverseZ = z != 0 ? 1 / z : 1;  // as OpenCV does for a point in the camera plane
  const double u = x * inverseZ, v = y * inverseZ;
  const double r2 = u * u + v * v;
  const double radial = 1 + intrinsics.k1 * r2 + intrinsics.k2 * r2 * r2;
  return {intrinsics.focalPx * u * radial + intrinsics.cx,
          intrinsics.focalPx * v * radial + intrinsics.cy};
}

}  // namespace parallax::vision
