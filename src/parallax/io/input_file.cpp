#include "parallax/io/input_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace parallax {

namespace {

std::string kindOf(mode_t mode) {
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a named pipe (FIFO)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

}  // namespace

std::string escapeControl(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  static const char kHex[] = "0123456789abcdef";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n')
      out += "\\n";
    else if (c == '\r')
      out += "\\r";
    else if (c == '\t')
      out += "\\t";
    else if (u < 0x20 || u == 0x7f)
      out += std::string("\\x") + kHex[u >> 4] + kHex[u & 15];
    else
      out += c;
  }
  return out;
}

InputError inputError(const std::string& file, const std::string& pointer,
                      const std::string& message) {
  return InputError(escapeControl(file), escapeControl(pointer), escapeControl(message));
}

void requireRegularFile(const std::string& path, const std::string& pointer) {
  struct stat info = {};
  if (::stat(path.c_str(), &info) != 0) {
    const int error = errno;
    if (error == ENOENT || error == ENOTDIR) throw inputError(path, pointer, "file not found");
    throw inputError(path, pointer,
                     std::string("cannot open the file (") + std::strerror(error) + ")");
  }
  if (S_ISREG(info.st_mode)) return;
  if (S_ISDIR(info.st_mode)) throw inputError(path, pointer, "is a folder, not a file");
  throw inputError(path, pointer, "not a regular file (" + kindOf(info.st_mode) + ")");
}

std::string readInputFile(const std::string& path, const std::string& pointer) {
  requireRegularFile(path, pointer);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw inputError(path, pointer, "cannot open the file (unreadable)");
  // Read at once into a string of the file's size: growing a stream buffer copied the bytes
  // again and again (a tenth of the time of reading the dragon's ASCII PLY, docs/import.md).
  std::error_code error;
  const uintmax_t size = std::filesystem::file_size(path, error);
  std::string bytes;
  if (!error && size > 0) {
    bytes.resize(size_t(size));
    in.read(bytes.data(), std::streamsize(size));
    bytes.resize(size_t(in.gcount()));
  }
  std::ostringstream rest;  // whatever the size did not say (a file that grew, /proc files)
  if (in.good() && in.peek() != std::ifstream::traits_type::eof()) {
    rest << in.rdbuf();
    bytes += std::move(rest).str();
  }
  if (in.bad()) throw inputError(path, pointer, "error while reading the file");
  return bytes;
}

}  // namespace parallax
