// The camera fit on synthetic views of a known phone camera, and projectPoint against OpenCV's
// own projection (calibrateCamera's per-view errors, which OpenCV computes with projectPoints).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/core/random.h"
#include "parallax/vision/vision.h"

namespace parallax::vision {
namespace {

using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec unit(const Vec& a) {
  const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  return {a[0] / n, a[1] / n, a[2] / n};
}
constexpr double kPi = 3.14159265358979323846;

// A camera at `centre` (display frame, mm) looking at `target`, turned `roll` radians about its
// axis. The camera frame is OpenCV's: x right, y down, z forward; the display's y is up.
CameraPose lookAt(const Vec& centre, const Vec& target, double roll = 0) {
  const Vec forward = unit(sub(target, centre));
  const Vec right0 = unit(cross(forward, {0, 1, 0}));
  const Vec down0 = cross(forward, right0);
  const double c = std::cos(roll), s = std::sin(roll);
  Vec right, down;
  for (int i = 0; i < 3; ++i) {
    right[i] = c * right0[i] + s * down0[i];
    down[i] = -s * right0[i] + c * down0[i];
  }
  CameraPose pose;
  pose.rotation = {right[0], right[1],   right[2],   down[0],   down[1],
                   down[2],  forward[0], forward[1], forward[2]};
  for (int i = 0; i < 3; ++i)
    pose.translation[i] =
        -(pose.rotation[3 * i] * centre[0] + pose.rotation[3 * i + 1] * centre[1] +
          pose.rotation[3 * i + 2] * centre[2]);
  return pose;
}

// A standard normal draw (Box-Muller).
double gaussian(Rng& rng) {
  const double u = (rng.next() + 1.0) / 4294967297.0, v = rng.next() / 4294967296.0;
  return std::sqrt(-2 * std::log(u)) * std::cos(2 * kPi * v);
}

// A 13 x 8 grid over a 527 x 296 mm panel, as the camera shows it (points outside the photo
// left out), with `noisePx` of Gaussian noise.
std::vector<PlaneCorrespondence> view(const CameraIntrinsics& camera, const CameraPose& pose,
                                      int width, int height, double noisePx, Rng& rng) {
  std::vector<PlaneCorrespondence> points;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 13; ++i) {
      const double x = -263.5 + 527.0 * i / 12, y = -148 + 296.0 * j / 7;
      PhotoPoint p = projectPoint(camera, pose, {x, y, 0});
      if (p.x < 0 || p.y < 0 || p.x > width || p.y > height) continue;
      p.x += noisePx * gaussian(rng);
      p.y += noisePx * gaussian(rng);
      points.push_back({x, y, p});
    }
  return points;
}

// sqrt of the mean squared distance between the points and their projection.
double rmsError(const CameraIntrinsics& camera, const CameraPose& pose,
                const std::vector<PlaneCorrespondence>& points) {
  double sum = 0;
  for (const PlaneCorrespondence& c : points) {
    const PhotoPoint p = projectPoint(camera, pose, {c.xMm, c.yMm, 0});
    sum += (p.x - c.photo.x) * (p.x - c.photo.x) + (p.y - c.photo.y) * (p.y - c.photo.y);
  }
  return std::sqrt(sum / double(points.size()));
}

const CameraIntrinsics kPhone{3000, 2016, 1512, -0.05, 0.02};
constexpr int kWidth = 4032, kHeight = 3024;

// Three views from 10 to 30 degrees off the panel's axis, 300 to 1200 mm away.
std::vector<CameraPose> threePoses() {
  const auto at = [](double degrees, double azimuth, double distance) {
    const double t = degrees * kPi / 180, a = azimuth * kPi / 180;
    return Vec{distance * std::sin(t) * std::cos(a), distance * std::sin(t) * std::sin(a),
               distance * std::cos(t)};
  };
  return {lookAt(at(10, 30, 600), {10, -5, 0}, 0.05), lookAt(at(20, 160, 300), {-40, 20, 0}),
          lookAt(at(30, 250, 1200), {0, 0, 0}, -0.1)};
}

TEST(ProjectPoint, PinholeWithRadialDistortion) {
  // On the axis: the principal point, in our convention (the photo's centre).
  const CameraPose front = lookAt({0, 0, 500}, {0, 0, 0});
  PhotoPoint p = projectPoint(kPhone, front, {0, 0, 0});
  EXPECT_NEAR(p.x, 2016, 1e-9);
  EXPECT_NEAR(p.y, 1512, 1e-9);
  // 100 mm right and up at 500 mm: x = 0.2, y = -0.2 (the display's up is the photo's up).
  p = projectPoint(kPhone, front, {100, 100, 0});
  const double r2 = 0.08, radial = 1 - 0.05 * r2 + 0.02 * r2 * r2;
  EXPECT_NEAR(p.x, 2016 + 3000 * 0.2 * radial, 1e-9);
  EXPECT_NEAR(p.y, 1512 - 3000 * 0.2 * radial, 1e-9);
}

TEST(FitCamera, RecoversAPhoneCamera) {
  Rng rng(7);
  std::vector<CameraPose> poses = threePoses();
  std::vector<std::vector<PlaneCorrespondence>> views;
  for (const CameraPose& pose : poses) {
    views.push_back(view(kPhone, pose, kWidth, kHeight, 0.1, rng));
    EXPECT_GE(views.back().size(), 40u);
  }
  const CameraFit fit = fitCamera(views, {"a.jpg", "b.jpg", "c.jpg"}, kWidth, kHeight);
  EXPECT_NEAR(fit.intrinsics.focalPx, 3000, 3000 * 0.005);
  EXPECT_GT(fit.focalSigmaPx, 0);
  EXPECT_LT(fit.focalSigmaPx, 3000 * 0.005);
  EXPECT_EQ(fit.intrinsics.cx, 2016);
  EXPECT_EQ(fit.intrinsics.cy, 1512);
  EXPECT_NEAR(fit.intrinsics.k1, -0.05, 0.01);
  EXPECT_NEAR(fit.intrinsics.k2, 0.02, 0.03);
  ASSERT_EQ(fit.poses.size(), 3u);
  ASSERT_EQ(fit.rmsErrorPx.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    const Vec truth = poses[i].cameraCentre(), found = fit.poses[i].cameraCentre();
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(found[k], truth[k], 3.0) << i << " " << k;
    // The noise's RMS (0.1 px in x and y: about 0.14 px), less what the fit absorbs.
    EXPECT_GT(fit.rmsErrorPx[i], 0.08);
    EXPECT_LT(fit.rmsErrorPx[i], 0.2);
    // projectPoint agrees with cv::projectPoints, which OpenCV's per-view error is made with.
    EXPECT_NEAR(rmsError(fit.viewIntrinsics[i], fit.poses[i], views[i]), fit.rmsErrorPx[i], 1e-4);
  }
}

TEST(FitCamera, ViewsOfThePhoneHeldEitherWay) {
  Rng rng(11);
  std::vector<CameraPose> poses = threePoses();
  poses.push_back(lookAt({150, -200, 800}, {0, 0, 0}, kPi / 2));  // held upright
  std::vector<std::vector<PlaneCorrespondence>> views;
  std::vector<PhotoSize> sizes;
  for (size_t i = 0; i < poses.size(); ++i) {
    const bool portrait = i == 3;
    CameraIntrinsics camera = kPhone;
    if (portrait) std::swap(camera.cx, camera.cy);
    sizes.push_back(portrait ? PhotoSize{kHeight, kWidth} : PhotoSize{kWidth, kHeight});
    views.push_back(view(camera, poses[i], sizes.back().width, sizes.back().height, 0.1, rng));
  }
  const CameraFit fit = fitCamera(views, {"a", "b", "c", "d"}, sizes);
  EXPECT_NEAR(fit.intrinsics.focalPx, 3000, 3000 * 0.005);
  ASSERT_EQ(fit.poses.size(), 4u);
  EXPECT_EQ(fit.viewIntrinsics[3].cx, 1512);
  EXPECT_EQ(fit.viewIntrinsics[3].cy, 2016);
  const Vec truth = poses[3].cameraCentre(), found = fit.poses[3].cameraCentre();
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(found[k], truth[k], 3.0) << k;
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(fit.poses[3].rotation[k], poses[3].rotation[k], 2e-3);
  for (size_t i = 0; i < 4; ++i)
    EXPECT_NEAR(rmsError(fit.viewIntrinsics[i], fit.poses[i], views[i]), fit.rmsErrorPx[i], 1e-4);
}

TEST(FitCamera, RefusesTooFewPointsAndAnotherCamera) {
  Rng rng(3);
  const std::vector<CameraPose> poses = threePoses();
  std::vector<std::vector<PlaneCorrespondence>> views;
  for (const CameraPose& pose : poses)
    views.push_back(view(kPhone, pose, kWidth, kHeight, 0.1, rng));
  views[1].resize(3);
  try {
    fitCamera(views, {"a.jpg", "b.jpg", "c.jpg"}, kWidth, kHeight);
    FAIL() << "fitted with 3 points";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "b.jpg");
    EXPECT_NE(std::string(e.what()).find("3 points found"), std::string::npos) << e.what();
  }
  views[1] = views[0];
  try {
    fitCamera(views, {"a.jpg", "b.jpg", "c.jpg"},
              {{kWidth, kHeight}, {kWidth, kHeight}, {4000, 3000}});
    FAIL() << "fitted photos of two cameras";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "c.jpg");
  }
}

}  // namespace
}  // namespace parallax::vision
