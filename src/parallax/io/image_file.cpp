#include "parallax/io/image_file.h"

#include <fcntl.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "parallax/core/error.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

std::string readFileBytes(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, "", "file not found");
  if (fs::is_directory(path, ec)) throw InputError(path, "", "is a folder, not an image file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  if (!(in && bytes << in.rdbuf())) throw InputError(path, "", "cannot read file");
  return bytes.str();
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

PfmHeader parsePfmHeader(const std::string& bytes, const std::string& path) {
  PfmHeader header;
  header.color = bytes[1] == 'F';
  size_t pos = 2;
  auto isSpace = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  auto nextToken = [&]() {
    if (pos >= bytes.size() || !isSpace(bytes[pos]))
      throw InputError(path, "", "malformed PFM header");
    while (pos < bytes.size() && isSpace(bytes[pos])) ++pos;
    const size_t start = pos;
    while (pos < bytes.size() && !isSpace(bytes[pos])) ++pos;
    return std::string_view(bytes).substr(start, pos - start);
  };
  auto parse = [&](std::string_view token, auto& value) {
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size())
      throw InputError(path, "", "malformed PFM header near '" + std::string(token) + "'");
  };
  parse(nextToken(), header.width);
  parse(nextToken(), header.height);
  double scale = 0;
  parse(nextToken(), scale);
  if (header.width <= 0 || header.height <= 0 || header.width > (1 << 16) ||
      header.height > (1 << 16))
    throw InputError(path, "", "PFM size out of range");
  if (scale == 0 || !std::isfinite(scale))
    throw InputError(path, "", "PFM scale must be non-zero (its sign gives the byte order)");
  header.littleEndian = scale < 0;
  if (pos >= bytes.size()) throw InputError(path, "", "truncated PFM: no pixel data");
  header.dataOffset = pos + 1;  // the single whitespace character after the scale
  return header;
}

Image decodePfm(const std::string& bytes, const std::string& path) {
  const PfmHeader header = parsePfmHeader(bytes, path);
  const int channels = header.color ? 3 : 1;
  const size_t expected = size_t(header.width) * size_t(header.height) * size_t(channels) * 4;
  const size_t available = bytes.size() - header.dataOffset;
  if (available < expected)
    throw InputError(path, "",
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

Image decodeWithStb(const std::string& bytes, const std::string& path) {
  if (bytes.size() > size_t(INT_MAX)) throw InputError(path, "", "image file too large");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = int(bytes.size());
  int width = 0, height = 0, channels = 0;
  auto fail = [&]() -> InputError {
    return InputError(path, "",
                      std::string("not a readable image (") + stbi_failure_reason() + ")");
  };
  if (stbi_is_hdr_from_memory(data, size)) {  // Radiance .hdr: already linear
    std::unique_ptr<float, void (*)(void*)> pixels(
        stbi_loadf_from_memory(data, size, &width, &height, &channels, 0), stbi_image_free);
    if (!pixels) throw fail();
    return imageFromCodes(pixels.get(), width, height, channels, [](float v) { return v; });
  }
  if (stbi_is_16_bit_from_memory(data, size)) {
    std::unique_ptr<stbi_us, void (*)(void*)> pixels(
        stbi_load_16_from_memory(data, size, &width, &height, &channels, 0), stbi_image_free);
    if (!pixels) throw fail();
    return imageFromCodes(pixels.get(), width, height, channels,
                          [](stbi_us code) { return srgbToLinear(float(code) / 65535.0f); });
  }
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(data, size, &width, &height, &channels, 0), stbi_image_free);
  if (!pixels) throw fail();
  return imageFromCodes(pixels.get(), width, height, channels, srgb8ToLinear);
}

}  // namespace

std::string pngBytes(const Image& image) {
  if (image.empty()) throw std::invalid_argument("pngBytes: empty image");
  std::vector<unsigned char> codes;
  codes.reserve(image.pixels().size() * 3);
  bool grey = true;
  for (const Vec3f& p : image.pixels()) {
    grey &= p.x == p.y && p.y == p.z;
    for (int c = 0; c < 3; ++c) codes.push_back(linearToSrgb8(p[c]));
  }
  // A grey picture (a mask layer, a calibration pattern) as one channel: a third of the bytes
  // to compress, and a file that says what it is.
  int channels = 3;
  if (grey) {
    for (size_t i = 0; i < image.pixels().size(); ++i) codes[i] = codes[3 * i];
    channels = 1;
  }
  std::string out;
  auto append = [](void* context, void* bytes, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(bytes), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &out, image.width(), image.height(), channels, codes.data(),
                              image.width() * channels))
    throw std::runtime_error("PNG encoding failed");
  return out;
}

namespace {

std::runtime_error ioFailure(const std::string& what, const std::string& path, int error) {
  return std::runtime_error("cannot " + what + " " + path + ": " +
                            std::error_code(error, std::generic_category()).message());
}

}  // namespace

Image readImage(const std::string& path) {
  const std::string bytes = readFileBytes(path);
  if (bytes.size() >= 2 && bytes[0] == 'P' && (bytes[1] == 'F' || bytes[1] == 'f'))
    return decodePfm(bytes, path);
  return decodeWithStb(bytes, path);
}

void writeImage(const std::string& path, const Image& image) {
  if (image.empty()) throw std::invalid_argument("writeImage: empty image for " + path);
  const std::string ext = lowerExtension(path);
  if (ext == ".png")
    writeFileAtomically(path, pngBytes(image));
  else if (ext == ".pfm")
    writeFileAtomically(path, encodePfm(image));
  else
    throw InputError(path, "", "unknown image format '" + ext + "' (write .png or .pfm)");
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
  const std::string temp = path + ".tmp-" + std::to_string(::getpid());
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
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
