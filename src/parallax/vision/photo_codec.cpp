// Decoding and encoding photos with OpenCV's codecs (libjpeg-turbo, libpng). The EXIF
// orientation is ours to apply: OpenCV is told to ignore it, so that the header we checked and
// the pixels we return can never disagree about which way is up.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "parallax/core/error.h"
#include "parallax/vision/vision.h"

namespace parallax::vision {
namespace {

struct Pixel {
  int x, y;
};

// Where the upright photo's pixel (x, y) is stored, for EXIF orientation 1 to 8 and a stored
// picture of storedWidth x storedHeight. The EXIF standard says where the stored 0th row and
// 0th column appear: 2 mirrored left-right; 3 turned half way; 4 mirrored top-bottom;
// 5 transposed (0th row on the left, 0th column on top); 6 0th row on the right, 0th column
// on top (turned a quarter clockwise); 7 0th row on the right, 0th column at the bottom;
// 8 0th row on the left, 0th column at the bottom (turned a quarter anticlockwise).
Pixel storedPixel(int orientation, int x, int y, int storedWidth, int storedHeight) {
  const int right = storedWidth - 1, bottom = storedHeight - 1;
  switch (orientation) {
    case 2:
      return {right - x, y};
    case 3:
      return {right - x, bottom - y};
    case 4:
      return {x, bottom - y};
    case 5:
      return {y, x};
    case 6:
      return {y, bottom - x};
    case 7:
      return {right - y, bottom - x};
    case 8:
      return {right - y, x};
    default:
      return {x, y};
  }
}

// The APP1 segment of an EXIF block whose IFD0 holds only the orientation (big-endian TIFF).
std::vector<uint8_t> exifSegment(int orientation) {
  return {
      0xFF, 0xE1,
      0,    34,  // APP1 and its length (counting itself)
      'E',  'x',
      'i',  'f',
      0,    0,  // the EXIF identifier
      'M',  'M',
      0,    42,
      0,    0,
      0,    8,  // TIFF: big-endian, IFD0 at offset 8
      0,    1,  // one entry:
      0x01, 0x12,
      0,    3,
      0,    0,
      0,    1,  //   orientation, SHORT, one value,
      0,    uint8_t(orientation),
      0,    0,  //   left-justified in the value field
      0,    0,
      0,    0,  // no IFD1
  };
}

}  // namespace

Photo decodePhoto(std::span<const uint8_t> bytes, const std::string& name, uint64_t maxPixels) {
  const PhotoHeader h = readPhotoHeader(bytes, name, maxPixels);
  if (bytes.size() > size_t(std::numeric_limits<int>::max()))  // OpenCV's Mat counts in int
    throw InputError(name, "", "a photo file of more than 2 GiB");
  const std::string what = h.format == PhotoFormat::Jpeg ? "JPEG" : "PNG";
  cv::Mat stored;
  try {
    // imdecode only reads its input; the Mat header merely wraps the caller's bytes.
    const cv::Mat encoded(1, int(bytes.size()), CV_8U, const_cast<uint8_t*>(bytes.data()));
    stored = cv::imdecode(encoded, cv::IMREAD_COLOR | cv::IMREAD_IGNORE_ORIENTATION);
  } catch (const cv::Exception&) {
    stored.release();  // reported below, as a decoder returning nothing is
  }
  if (stored.empty() || stored.type() != CV_8UC3)
    throw InputError(name, "", "the " + what + " does not decode");
  if (stored.cols != h.storedWidth || stored.rows != h.storedHeight)
    throw InputError(name, "",
                     "the " + what + " decodes to " + std::to_string(stored.cols) + "x" +
                         std::to_string(stored.rows) + " pixels, not its header's " +
                         std::to_string(h.storedWidth) + "x" + std::to_string(h.storedHeight));
  Photo photo;
  photo.width = h.width;
  photo.height = h.height;
  photo.rgb.resize(size_t(h.width) * size_t(h.height) * 3);
  uint8_t* out = photo.rgb.data();
  for (int y = 0; y < h.height; ++y) {
    for (int x = 0; x < h.width; ++x, out += 3) {
      const Pixel s = storedPixel(h.orientation, x, y, h.storedWidth, h.storedHeight);
      const uint8_t* bgr = stored.ptr<uint8_t>(s.y) + 3 * size_t(s.x);
      out[0] = bgr[2];
      out[1] = bgr[1];
      out[2] = bgr[0];
    }
  }
  return photo;
}

std::vector<uint8_t> encodeJpeg(const Photo& photo, int quality, int orientation) {
  if (photo.width <= 0 || photo.height <= 0 ||
      photo.rgb.size() != size_t(photo.width) * size_t(photo.height) * 3)
    throw std::invalid_argument("encodeJpeg: a photo without pixels or of the wrong size");
  if (quality < 1 || quality > 100) throw std::invalid_argument("encodeJpeg: quality not 1-100");
  if (orientation < 1 || orientation > 8)
    throw std::invalid_argument("encodeJpeg: orientation not 1-8");
  const bool turned = orientation >= 5;
  const int storedWidth = turned ? photo.height : photo.width;
  const int storedHeight = turned ? photo.width : photo.height;
  // Every upright pixel goes where a reader applying the orientation will fetch it from.
  cv::Mat stored(storedHeight, storedWidth, CV_8UC3);
  const uint8_t* in = photo.rgb.data();
  for (int y = 0; y < photo.height; ++y) {
    for (int x = 0; x < photo.width; ++x, in += 3) {
      const Pixel s = storedPixel(orientation, x, y, storedWidth, storedHeight);
      uint8_t* bgr = stored.ptr<uint8_t>(s.y) + 3 * size_t(s.x);
      bgr[0] = in[2];
      bgr[1] = in[1];
      bgr[2] = in[0];
    }
  }
  std::vector<uint8_t> jpeg;
  // OpenCV's defaults are a baseline (not progressive), unoptimised JPEG.
  if (!cv::imencode(".jpg", stored, jpeg, {cv::IMWRITE_JPEG_QUALITY, quality}))
    throw std::runtime_error("encodeJpeg: OpenCV's JPEG encoder failed");
  if (orientation != 1) {
    // EXIF wants its APP1 right after SOI (before OpenCV's JFIF APP0).
    const std::vector<uint8_t> exif = exifSegment(orientation);
    jpeg.insert(jpeg.begin() + 2, exif.begin(), exif.end());
  }
  return jpeg;
}

}  // namespace parallax::vision
