// Computer vision for calibration from photos, behind our own small interface: OpenCV (Debian's,
// 4.6 on Debian 12 with ArUco in contrib, 4.10 on Debian 13 with ArUco in objdetect) is included
// only in this module's .cpp files. Photos are untrusted bytes from a phone: the header is read
// and the memory estimated before anything is decoded (docs/calibration.md, "From photos").
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace parallax::vision {

// A point in a photo, in pixels: x right, y down, (0, 0) the top-left pixel's top-left corner,
// so that pixel (i, j) is centred at (i + 0.5, j + 0.5).
struct PhotoPoint {
  double x = 0, y = 0;
};

// An 8-bit sRGB photo as the camera stored it, upright (its EXIF orientation applied), row 0 at
// the top, 3 bytes per pixel (R, G, B).
struct Photo {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

enum class PhotoFormat { Jpeg, Png };

// What the file's header says, read without decoding: the stored size, the EXIF orientation
// (1 to 8; 1 when there is none) and the size once upright (5 to 8 swap width and height).
struct PhotoHeader {
  PhotoFormat format = PhotoFormat::Jpeg;
  int storedWidth = 0, storedHeight = 0;
  int orientation = 1;
  int width = 0, height = 0;
  uint64_t decodeBytes = 0;  // the memory decoding takes, estimated from the header
};

// Reads a JPEG's or PNG's header from its bytes. Throws InputError(name, "", why) for anything
// else, a truncated or lying header, or a size of 0 or above maxPixels.
PhotoHeader readPhotoHeader(std::span<const uint8_t> bytes, const std::string& name,
                            uint64_t maxPixels);
// Decodes after readPhotoHeader's checks, then applies the EXIF orientation. Throws InputError
// naming `name` for a file that does not decode.
Photo decodePhoto(std::span<const uint8_t> bytes, const std::string& name, uint64_t maxPixels);
// Encodes as a baseline JPEG (quality 1 to 100), with an EXIF orientation tag when orientation
// is not 1: the stored pixels are then `photo` turned so that a reader applying the tag gets
// `photo` back (the photo maker's phones write both kinds).
std::vector<uint8_t> encodeJpeg(const Photo& photo, int quality, int orientation = 1);

// ArUco markers (OpenCV's DICT_4X4_250): 4x4 data cells inside a one-cell black border.
inline constexpr int kMarkerCells = 6;  // cells per side, border included
int markerDictionarySize();
// The marker's cells, row by row from the top, kMarkerCells^2 of them: 0 black, 1 white.
std::vector<uint8_t> markerCells(int id);

// One marker found in a photo: its corners in the order the marker is drawn (top-left,
// top-right, bottom-right, bottom-left of markerCells), refined to subpixel precision.
struct DetectedMarker {
  int id = 0;
  std::array<PhotoPoint, 4> corners;
};
std::vector<DetectedMarker> detectMarkers(const Photo& photo);  // in order of id

// A point of the panel plane (z = 0 of the display frame, mm: x right, y up, origin at the
// panel's centre) and where one photo shows it.
struct PlaneCorrespondence {
  double xMm = 0, yMm = 0;
  PhotoPoint photo;
};

// The camera: a pinhole with square pixels, its principal point at (cx, cy) (in PhotoPoint's
// convention: a photo's centre is (width / 2, height / 2)), and radial distortion (OpenCV's k1,
// k2: x_d = x (1 + k1 r^2 + k2 r^4) in normalised coordinates).
struct CameraIntrinsics {
  double focalPx = 0;
  double cx = 0, cy = 0;
  double k1 = 0, k2 = 0;
};

// Where a camera stood for one photo: X_camera = R X_display + t (mm; OpenCV's camera frame:
// x right, y down, z forward). cameraCentre() is -R^T t in the display frame.
struct CameraPose {
  std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major R
  std::array<double, 3> translation{};
  std::array<double, 3> cameraCentre() const;
};

struct CameraFit {
  CameraIntrinsics intrinsics;     // for photos of the first view's size
  double focalSigmaPx = 0;         // the focal length's standard deviation from the fit
  std::vector<CameraPose> poses;   // one per view, in order
  std::vector<double> rmsErrorPx;  // each view's reprojection error
  // Each view's own intrinsics: `intrinsics`, with the principal point at that view's centre
  // (cx and cy swapped for a view of the other orientation). projectPoint(viewIntrinsics[i],
  // poses[i], p) is where view i shows p.
  std::vector<CameraIntrinsics> viewIntrinsics;
};

// Fits one camera (focal length, k1, k2; the principal point at the photos' centre) and a pose
// per view to planar correspondences, all views taken by that camera (same width x height).
// Throws InputError(names[i], "", why) when a view has too few points (4) or the fit fails.
CameraFit fitCamera(const std::vector<std::vector<PlaneCorrespondence>>& views,
                    const std::vector<std::string>& names, int width, int height);

struct PhotoSize {
  int width = 0, height = 0;
};
// The same, each view with its own photo's size: the phone may be held either way, so a view
// of height x width (the first view's size turned) is fitted as the same camera, turned about
// its axis; its pose is in its own photo's frame. Throws InputError(names[i], "", why) also for
// a view of another size.
CameraFit fitCamera(const std::vector<std::vector<PlaneCorrespondence>>& views,
                    const std::vector<std::string>& names, const std::vector<PhotoSize>& sizes);

// Where the camera shows a display-frame point (mm), distortion included.
PhotoPoint projectPoint(const CameraIntrinsics& intrinsics, const CameraPose& pose,
                        const std::array<double, 3>& pointMm);

}  // namespace parallax::vision
