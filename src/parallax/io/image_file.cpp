#include "parallax/io/image_file.h"

#include <fcntl.h>
#include <stb_image.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <type_traits>

#include "parallax/core/error.h"
#include "parallax/core/output_path.h"
#include "parallax/core/parallel.h"
#include "parallax/io/input_file.h"
#include "parallax/io/png_encoder.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// ---- What the bytes are, and whether the name agrees -----------------------------------

enum class Format { Png, Jpeg, Pfm, Hdr, Bmp, Gif, Psd, Pnm, Tga, Unknown };

const char* formatName(Format f) {
  switch (f) {
    case Format::Png:
      return "PNG";
    case Format::Jpeg:
      return "JPEG";
    case Format::Pfm:
      return "PFM";
    case Format::Hdr:
      return "Radiance HDR";
    case Format::Bmp:
      return "BMP";
    case Format::Gif:
      return "GIF";
    case Format::Psd:
      return "PSD";
    case Format::Pnm:
      return "PNM";
    case Format::Tga:
      return "TGA";
    case Format::Unknown:
      break;
  }
  return "unknown";
}

// The format the first bytes announce. TGA has no signature: it is what the name says.
Format sniffFormat(std::string_view b) {
  const auto starts = [&b](std::string_view magic) { return b.substr(0, magic.size()) == magic; };
  if (starts("\x89PNG\r\n\x1a\n")) return Format::Png;
  if (starts("\xff\xd8\xff")) return Format::Jpeg;
  if (b.size() >= 2 && b[0] == 'P' && (b[1] == 'F' || b[1] == 'f')) return Format::Pfm;
  if (starts("#?RADIANCE") || starts("#?RGBE")) return Format::Hdr;
  if (starts("BM")) return Format::Bmp;
  if (starts("GIF8")) return Format::Gif;
  if (starts("8BPS")) return Format::Psd;
  if (b.size() >= 2 && b[0] == 'P' && (b[1] == '5' || b[1] == '6')) return Format::Pnm;
  return Format::Unknown;
}

// The format an image extension claims, or Unknown for a name that claims none.
Format claimedFormat(const std::string& ext) {
  if (ext == ".png") return Format::Png;
  if (ext == ".jpg" || ext == ".jpeg") return Format::Jpeg;
  if (ext == ".pfm") return Format::Pfm;
  if (ext == ".hdr") return Format::Hdr;
  if (ext == ".bmp") return Format::Bmp;
  if (ext == ".gif") return Format::Gif;
  if (ext == ".psd") return Format::Psd;
  if (ext == ".pnm" || ext == ".ppm" || ext == ".pgm") return Format::Pnm;
  if (ext == ".tga") return Format::Tga;
  return Format::Unknown;
}

// The format to decode `bytes` as, or an InputError when they are no supported image or are
// another format than the file's extension claims.
Format checkedFormat(std::string_view bytes, const std::string& name) {
  const Format claimed = claimedFormat(lowerExtension(name));
  Format found = sniffFormat(bytes);
  if (found == Format::Unknown && claimed == Format::Tga) found = Format::Tga;
  if (found == Format::Unknown)
    throw inputError(name, "",
                     "not a readable image (unknown format; PNG, JPEG, PFM and HDR are read)");
  if (claimed != Format::Unknown && claimed != found)
    throw inputError(name, "",
                     std::string("not a readable image: the name says ") + formatName(claimed) +
                         " but the contents are " + formatName(found));
  return found;
}

std::string gibText(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", bytes / double(1ull << 30));
  return text;
}

// Refuses, from the header alone, an image whose pixels would take more memory than
// kMaxImageDecodeBytes (decoded codes plus the linear float image) or more than
// kMaxImageSide pixels a side: a small crafted file can announce gigabytes.
void checkImageSize(const std::string& name, int64_t width, int64_t height,
                    double bytesPerPixelDecoded) {
  if (width < 1 || height < 1)
    throw inputError(
        name, "",
        "image size " + std::to_string(width) + "x" + std::to_string(height) + " has no pixels");
  const double needed =
      double(width) * double(height) * (bytesPerPixelDecoded + double(sizeof(Vec3f)));
  if (width > kMaxImageSide || height > kMaxImageSide || needed > double(kMaxImageDecodeBytes))
    throw inputError(name, "",
                     "needs about " + gibText(needed) + " to decode " + std::to_string(width) +
                         "x" + std::to_string(height) + " pixels (limit " +
                         gibText(double(kMaxImageDecodeBytes)) + ", at most " +
                         std::to_string(kMaxImageSide) + " pixels a side)");
}

// ---- PFM (Portable Float Map) -------------------------------------------------------------
// Header: "PF" (RGB) or "Pf" (grey), width, height and a scale whose sign gives the byte
// order (negative: little-endian), separated by whitespace, then exactly one whitespace
// character and width*height*channels 32-bit floats, rows from the bottom of the image up.

struct PfmHeader {
  bool color = true;
  int width = 0, height = 0;
  bool littleEndian = true;
  size_t dataOffset = 0;
};

PfmHeader parsePfmHeader(std::string_view bytes, const std::string& path) {
  PfmHeader header;
  header.color = bytes[1] == 'F';
  size_t pos = 2;
  auto isSpace = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  auto nextToken = [&]() {
    if (pos >= bytes.size() || !isSpace(bytes[pos]))
      throw inputError(path, "", "malformed PFM header");
    while (pos < bytes.size() && isSpace(bytes[pos])) ++pos;
    const size_t start = pos;
    while (pos < bytes.size() && !isSpace(bytes[pos])) ++pos;
    return bytes.substr(start, pos - start);
  };
  auto parse = [&](std::string_view token, auto& value) {
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size())
      throw inputError(path, "", "malformed PFM header near '" + std::string(token) + "'");
  };
  parse(nextToken(), header.width);
  parse(nextToken(), header.height);
  double scale = 0;
  parse(nextToken(), scale);
  if (header.width <= 0 || header.height <= 0) throw inputError(path, "", "PFM size out of range");
  checkImageSize(path, header.width, header.height, header.color ? 12.0 : 4.0);
  if (scale == 0 || !std::isfinite(scale))
    throw inputError(path, "", "PFM scale must be non-zero (its sign gives the byte order)");
  header.littleEndian = scale < 0;
  if (pos >= bytes.size()) throw inputError(path, "", "truncated PFM: no pixel data");
  header.dataOffset = pos + 1;  // the single whitespace character after the scale
  return header;
}

Image decodePfm(std::string_view bytes, const std::string& path) {
  const PfmHeader header = parsePfmHeader(bytes, path);
  const int channels = header.color ? 3 : 1;
  const size_t expected = size_t(header.width) * size_t(header.height) * size_t(channels) * 4;
  const size_t available = bytes.size() - header.dataOffset;
  if (available < expected)
    throw inputError(path, "",
                     "truncated PFM: " + std::to_string(available) +
                         " bytes of pixel data, expected " + std::to_string(expected));
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data() + header.dataOffset);
  auto readFloat = [&](size_t index) {
    const unsigned char* b = data + 4 * index;
    const uint32_t bits =
        header.littleEndian
            ? uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24
            : uint32_t(b[3]) | uint32_t(b[2]) << 8 | uint32_t(b[1]) << 16 | uint32_t(b[0]) << 24;
    return std::bit_cast<float>(bits);
  };
  Image image(header.width, header.height);
  size_t index = 0;
  for (int fileRow = 0; fileRow < header.height; ++fileRow) {
    const int y = header.height - 1 - fileRow;
    for (int x = 0; x < header.width; ++x) {
      Vec3f& p = image.at(x, y);
      if (header.color) {
        p.x = readFloat(index++);
        p.y = readFloat(index++);
        p.z = readFloat(index++);
      } else {
        p = Vec3f(readFloat(index++));
      }
      if (!isFinite(p))
        throw inputError(path, "",
                         "pixel (" + std::to_string(x) + ", " + std::to_string(fileRow) +
                             ") of the PFM (counted from its first row) is NaN or infinite");
    }
  }
  return image;
}

std::string encodePfm(const Image& image) {
  std::string out =
      "PF\n" + std::to_string(image.width()) + " " + std::to_string(image.height()) + "\n-1\n";
  out.reserve(out.size() + size_t(image.width()) * size_t(image.height()) * 12);
  for (int y = image.height() - 1; y >= 0; --y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const auto bits = std::bit_cast<uint32_t>(image.at(x, y)[c]);
        for (int byte = 0; byte < 4; ++byte) out += char((bits >> (8 * byte)) & 0xFF);
      }
  return out;
}

// ---- PNG, JPEG and the other formats stb_image reads --------------------------------------

// 8- and 16-bit files hold sRGB-encoded codes; grey is replicated and alpha is dropped
// (textures use the colour as stored, PNG alpha is not premultiplied).
template <typename Code, typename Decode>
Image imageFromCodes(const Code* codes, int width, int height, int channels, Decode decode) {
  Image image(width, height);
  const bool grey = channels <= 2;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Code* p = codes + (size_t(y) * size_t(width) + size_t(x)) * size_t(channels);
      image.at(x, y) = grey ? Vec3f(decode(p[0])) : Vec3f(decode(p[0]), decode(p[1]), decode(p[2]));
    }
  return image;
}

// The length of a binary PNM header ("P5" or "P6", then width, height and maxval separated by
// whitespace or # comments, then one whitespace byte): where the samples begin.
size_t pnmHeaderLength(std::string_view b) {
  size_t i = 2;
  for (int field = 0; field < 3; ++field) {
    while (i < b.size() && (std::isspace(static_cast<unsigned char>(b[i])) || b[i] == '#')) {
      if (b[i] == '#')
        while (i < b.size() && b[i] != '\n' && b[i] != '\r') ++i;
      else
        ++i;
    }
    while (i < b.size() && std::isdigit(static_cast<unsigned char>(b[i]))) ++i;
  }
  return i + 1;  // the one whitespace byte after maxval
}

// Decodes what stb_image reads, after checking the header, and hands the decoded samples to
// `sink(codes, width, height, channels)` (codes: float for Radiance HDR, stbi_us for 16-bit
// files, stbi_uc otherwise), returning what it makes.
template <typename Sink>
auto decodeWithStb(std::string_view bytes, const std::string& path, Sink sink) {
  if (bytes.size() > size_t(INT_MAX)) throw inputError(path, "", "image file too large");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = int(bytes.size());
  auto fail = [&]() -> InputError {
    return inputError(path, "",
                      std::string("not a readable image (") + stbi_failure_reason() + ")");
  };
  // The header first: stb_image would otherwise allocate whatever the file announces. A PNG's
  // IHDR is read here, since stb_image's own check of it ends in a vague "unknown image type".
  if (bytes.size() >= 26 && sniffFormat(bytes) == Format::Png && bytes.substr(12, 4) == "IHDR") {
    const auto u8 = [&bytes](size_t i) { return uint32_t(static_cast<unsigned char>(bytes[i])); };
    const auto be32 = [&u8](size_t i) {
      return u8(i) << 24 | u8(i + 1) << 16 | u8(i + 2) << 8 | u8(i + 3);
    };
    const uint32_t colourType = u8(25);
    const double pngChannels = colourType == 0 ? 1 : colourType == 4 ? 2 : colourType == 6 ? 4 : 3;
    checkImageSize(path, be32(16), be32(20), pngChannels * (u8(24) == 16 ? 2 : 1));
  }
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &width, &height, &channels)) throw fail();
  const bool hdr = stbi_is_hdr_from_memory(data, size) != 0;
  const bool wide = !hdr && stbi_is_16_bit_from_memory(data, size) != 0;
  checkImageSize(path, width, height, double(std::max(channels, 1)) * (hdr ? 4 : wide ? 2 : 1));
  // Binary PNM stores its samples uncompressed after the header, so the file holds exactly
  // width x height x channels samples there; stb_image pads a shorter file with zeros, after
  // allocating and converting everything a few header bytes announce (found by fuzzing).
  if (sniffFormat(bytes) == Format::Pnm) {
    const double needed =
        double(width) * double(height) * double(std::max(channels, 1)) * (wide ? 2.0 : 1.0);
    const size_t header = pnmHeaderLength(bytes);
    const double held = double(bytes.size() - std::min(header, bytes.size()));
    if (held < needed)
      throw inputError(path, "",
                       "truncated: the header announces " + std::to_string(width) + "x" +
                           std::to_string(height) + " pixels (" + std::to_string(int64_t(needed)) +
                           " bytes of samples), the file " + "holds " +
                           std::to_string(int64_t(held)));
  }
  const int expectedWidth = width, expectedHeight = height;
  const auto sameSize = [&]() {
    if (width != expectedWidth || height != expectedHeight || channels < 1 || channels > 4)
      throw inputError(path, "", "not a readable image (decoded size differs from its header)");
  };
  if (hdr) {  // Radiance .hdr: already linear
    std::unique_ptr<float, void (*)(void*)> pixels(
        stbi_loadf_from_memory(data, size, &width, &height, &channels, 0), stbi_image_free);
    if (!pixels) throw fail();
    sameSize();
    return sink(static_cast<const float*>(pixels.get()), width, height, channels);
  }
  if (wide) {
    std::unique_ptr<stbi_us, void (*)(void*)> pixels(
        stbi_load_16_from_memory(data, size, &width, &height, &channels, 0), stbi_image_free);
    if (!pixels) throw fail();
    sameSize();
    return sink(static_cast<const stbi_us*>(pixels.get()), width, height, channels);
  }
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(data, size, &width, &height, &channels, 0), stbi_image_free);
  if (!pixels) throw fail();
  sameSize();
  return sink(static_cast<const stbi_uc*>(pixels.get()), width, height, channels);
}

// Linear RGB: 8- and 16-bit codes through the sRGB transfer function, HDR floats as they are.
Image decodeWithStb(std::string_view bytes, const std::string& path) {
  return decodeWithStb(bytes, path, [](const auto* codes, int width, int height, int channels) {
    using Code = std::remove_cv_t<std::remove_pointer_t<decltype(codes)>>;
    if constexpr (std::is_same_v<Code, float>)
      return imageFromCodes(codes, width, height, channels, [](float v) { return v; });
    else if constexpr (std::is_same_v<Code, stbi_us>)
      return imageFromCodes(codes, width, height, channels,
                            [](stbi_us code) { return srgbToLinear(float(code) / 65535.0f); });
    else
      return imageFromCodes(codes, width, height, channels, srgb8ToLinear);
  });
}

// The samples as stored: each code over the largest code of its bit depth, floats as they are.
ImageSamples samplesWithStb(std::string_view bytes, const std::string& path) {
  return decodeWithStb(bytes, path, [](const auto* codes, int width, int height, int channels) {
    using Code = std::remove_cv_t<std::remove_pointer_t<decltype(codes)>>;
    ImageSamples out;
    out.width = width;
    out.height = height;
    out.channels = channels;
    out.bitsPerSample = std::is_same_v<Code, float> ? 32 : int(8 * sizeof(Code));
    const double scale = std::is_same_v<Code, float>     ? 1.0
                         : std::is_same_v<Code, stbi_us> ? 1.0 / 65535.0
                                                         : 1.0 / 255.0;
    out.samples.resize(size_t(width) * size_t(height) * size_t(channels));
    for (size_t i = 0; i < out.samples.size(); ++i)
      out.samples[i] = float(double(codes[i]) * scale);
    return out;
  });
}

}  // namespace

std::string pngBytes(const Image& image, bool greyAsOneChannel) {
  if (image.empty()) throw std::invalid_argument("pngBytes: empty image");
  const int width = image.width(), height = image.height();
  const size_t rowPixels = size_t(width);
  std::vector<uint8_t> codes(image.pixels().size() * 3);
  // sRGB codes on every core, in bands of rows (each pixel's codes do not depend on the band).
  const int64_t bandRows = std::max<int64_t>(1, 65536 / width);
  parallelFor(height, 0, bandRows, [&](int64_t begin, int64_t end) {
    const size_t first = size_t(begin) * rowPixels, pixels = size_t(end - begin) * rowPixels;
    linearToSrgb8(&image.pixels()[first].x, 3 * pixels, codes.data() + 3 * first);
  });
  return pngBytesFromSrgb8(codes, width, height, greyAsOneChannel);
}

std::string pngBytesFromSrgb8(std::vector<uint8_t>& rgbCodes, int width, int height,
                              bool greyAsOneChannel) {
  if (width <= 0 || height <= 0 || rgbCodes.size() != size_t(width) * size_t(height) * 3)
    throw std::invalid_argument("pngBytesFromSrgb8: codes do not match the size");
  // A grey picture (a mask layer, a calibration pattern) as one channel: a third of the bytes
  // to compress, and a file that says what it is.
  const size_t pixels = rgbCodes.size() / 3;
  bool grey = greyAsOneChannel;
  for (size_t i = 0; grey && i < pixels; ++i)
    grey = rgbCodes[3 * i] == rgbCodes[3 * i + 1] && rgbCodes[3 * i + 1] == rgbCodes[3 * i + 2];
  if (grey) {
    std::vector<uint8_t> single(pixels);
    for (size_t i = 0; i < pixels; ++i) single[i] = rgbCodes[3 * i];
    return encodePng(single.data(), width, height, 1);
  }
  return encodePng(rgbCodes.data(), width, height, 3);
}

namespace {

std::runtime_error ioFailure(const std::string& what, const std::string& path, int error) {
  return std::runtime_error("cannot " + what + " " + path + ": " +
                            std::error_code(error, std::generic_category()).message());
}

}  // namespace

Image decodeImage(std::string_view bytes, const std::string& name) {
  if (checkedFormat(bytes, name) == Format::Pfm) return decodePfm(bytes, name);
  return decodeWithStb(bytes, name);
}

Image readImage(const std::string& path) {
  return decodeImage(readInputFile(path), path);
}

ImageInfo readImageInfo(const std::string& path) {
  ImageInfo info;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || !stbi_info(path.c_str(), &info.width, &info.height, &info.channels)) return {};
  info.fileBytes = double(size);
  info.bytesPerSample = stbi_is_hdr(path.c_str()) ? 4 : stbi_is_16_bit(path.c_str()) ? 2 : 1;
  return info;
}

ImageSamples readImageSamples(const std::string& path) {
  const std::string bytes = readInputFile(path);
  if (checkedFormat(bytes, path) != Format::Pfm) return samplesWithStb(bytes, path);
  // PFM holds linear floats already: its RGB (grey is replicated) as stored.
  const Image image = decodePfm(bytes, path);
  ImageSamples out;
  out.width = image.width();
  out.height = image.height();
  out.channels = 3;
  out.bitsPerSample = 32;
  out.samples.reserve(image.pixels().size() * 3);
  for (const Vec3f& p : image.pixels()) out.samples.insert(out.samples.end(), {p.x, p.y, p.z});
  return out;
}

void writeImage(const std::string& path, const Image& image) {
  if (image.empty()) throw std::invalid_argument("writeImage: empty image for " + path);
  const std::string ext = lowerExtension(path);
  if (ext == ".png")
    writeFileAtomically(path, pngBytes(image));
  else if (ext == ".pfm")
    writeFileAtomically(path, encodePfm(image));
  else
    throw inputError(path, "", "unknown image format '" + ext + "' (write .png or .pfm)");
}

void writeFileAtomically(const std::string& path, std::string_view bytes) {
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent)) {
    fs::create_directories(parent, ec);
    if (ec) throw ioFailure("create the folder for", path, ec.value());
  }
  // The temporary name lives in the target's folder so that rename() stays on one file system
  // and is atomic: readers see either the old file or the complete new one.
  // FILE.tmp-PID of killed runs go; this process's own name is made afresh (O_EXCL, no link
  // followed: whatever held the name is not written through).
  removeStaleTemporaryFiles(path);
  const std::string temp = path + ".tmp-" + std::to_string(::getpid());
  ::unlink(temp.c_str());
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) throw ioFailure("write", path, errno);
  size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : EIO;
      ::close(fd);
      ::unlink(temp.c_str());
      throw ioFailure("write", path, error);
    }
    written += size_t(n);
  }
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(temp.c_str());
    throw ioFailure("write", path, error);
  }
  fs::rename(temp, path, ec);
  if (ec) {
    ::unlink(temp.c_str());
    throw ioFailure("replace", path, ec.value());
  }
}

}  // namespace parallax
