// Third-party importers in a child process (docs/import.md, "Isolation"), as browsers parse
// untrusted content out of process: assimp is a large C++ library that parses untrusted bytes,
// and crafted files make it free twice, dereference wild pointers or allocate without bound
// (../shared/reliability). fork() needs no helper binary to find, so it works alike for the
// command line, libparallax.so and the Python module. The child
//  - sets its limits: address space (what it has at the fork + the memory budget, so that an
//    ASan build's huge shadow reservation does not count), CPU time, no core dump;
//  - keeps no descriptor of the parent but the result memfd (stdin, stdout and stderr go to
//    /dev/null), so nothing it does reaches the user's files or terminal;
//  - reads and converts the file (textures too), writes FileContents in our flat layout to the
//    memfd and leaves with _exit (no atexit handler, no stdio flush, no Python finalisation).
// The parent waits with a wall-clock deadline (a child that hangs without burning CPU) and
// watches the child's private memory (the address-space limit does not bound an ASan build's
// allocator, whose regions are reserved up front), kills it if needed, reaps it in every path,
// and parses the blob with every count checked against the bytes present.
#include "parallax/importer/isolated_import.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <new>
#include <type_traits>

#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/importer/assimp_importer.h"

#if defined(__SANITIZE_ADDRESS__)
#define PARALLAX_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PARALLAX_ASAN 1
#endif
#endif
#ifdef PARALLAX_ASAN
#include <sanitizer/common_interface_defs.h>
#endif

namespace parallax {

namespace {

std::mutex& limitsMutex() {
  static std::mutex m;
  return m;
}
ImporterLimits& storedLimits() {
  static ImporterLimits limits;
  return limits;
}

}  // namespace

void setImporterLimits(const ImporterLimits& limits) {
  std::lock_guard lock(limitsMutex());
  storedLimits() = limits;
}

ImporterLimits importerLimits() {
  ImporterLimits limits;
  {
    std::lock_guard lock(limitsMutex());
    limits = storedLimits();
  }
  if (!(limits.memoryBytes > 0))
    limits.memoryBytes = defaultMemoryLimitBytes(physicalMemoryBytes());
  if (!(limits.cpuSeconds > 0)) limits.cpuSeconds = kDefaultImporterCpuSeconds;
  return limits;
}

namespace meshio {

void (*childFaultForTests)() = nullptr;

namespace {

// ---- the flat layout ----------------------------------------------------------------------
// magic, kind, then for contents: images, materials, parts, warnings, note, droppedDegenerate,
// declaredUp; for a refusal: the InputError's file, key and text; then the end magic. Counts
// are uint64, arrays their elements' bytes, strings a uint64 length and the bytes.

constexpr uint64_t kMagic = 0x31504d49584c5050ull;     // "PPLXIMP1"
constexpr uint64_t kEndMagic = 0x31444e45584c5050ull;  // "PPLXEND1"
enum Kind : uint32_t { kContents = 1, kRefusal = 2 };

// A new field in these structs must be carried by the layout (and compared by the round-trip
// test): these sizes fail the build first.
static_assert(sizeof(Material) == sizeof(std::string) + 40, "Material: update the flat layout");
static_assert(sizeof(FileMaterial) == sizeof(Material) + 8, "FileMaterial: update the layout");
// (FilePart: context, material and its padding, the transform, node and its padding, five
// vectors and the node names.)
static_assert(sizeof(FilePart) == sizeof(std::string) + 8 + sizeof(Transform) + 8 +
                                      5 * sizeof(std::vector<int>) +
                                      sizeof(std::vector<std::string>),
              "FilePart: update the flat layout");

class Writer {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  template <typename T, typename Allocator>
  void array(const std::vector<T, Allocator>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(uint64_t(values.size()));
    if (!values.empty())
      out_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void string(const std::string& text) {
    put(uint64_t(text.size()));
    out_ += text;
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

struct Garbled {
  std::string what;
};

class Reader {
 public:
  explicit Reader(std::string_view blob) : data_(blob) {}

  template <typename T>
  T get(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (data_.size() < sizeof(T)) throw Garbled{std::string("truncated at ") + what};
    T value;
    std::memcpy(&value, data_.data(), sizeof(T));
    data_.remove_prefix(sizeof(T));
    return value;
  }
  // A count of items of at least `minimumBytes` each: never more than the bytes left hold.
  size_t count(size_t minimumBytes, const char* what) {
    const uint64_t n = get<uint64_t>(what);
    if (n > data_.size() / std::max<size_t>(minimumBytes, 1))
      throw Garbled{std::string(what) + ": count " + std::to_string(n) +
                    " beyond the bytes present"};
    return size_t(n);
  }
  template <typename T, typename Allocator = std::allocator<T>>
  std::vector<T, Allocator> array(const char* what) {
    const size_t n = count(sizeof(T), what);
    std::vector<T, Allocator> values(n);
    if (n > 0) std::memcpy(values.data(), data_.data(), n * sizeof(T));  // no null pointer
    data_.remove_prefix(n * sizeof(T));
    return values;
  }
  std::string string(const char* what) {
    const size_t n = count(1, what);
    std::string text(data_.substr(0, n));
    data_.remove_prefix(n);
    return text;
  }
  bool atEnd() const { return data_.empty(); }

 private:
  std::string_view data_;
};

void putTransform(Writer& w, const Transform& t) {
  w.put(t.matrix());
  w.put(t.inverseMatrix());
}

void putMaterial(Writer& w, const Material& m) {
  w.string(m.name);
  w.put(m.diffuse);
  w.put(int32_t(m.diffuseTexture));
  w.put(m.mirror);
  w.put(m.emission);
}

// An index into a list of `size` items, or -1.
int indexOrNone(Reader& r, size_t size, const char* what) {
  const int32_t index = r.get<int32_t>(what);
  if (index < -1 || (index >= 0 && size_t(index) >= size))
    throw Garbled{std::string(what) + " " + std::to_string(index) + " out of range"};
  return index;
}

// Normals, UVs and colours: none or one per position.
template <typename T>
std::vector<T> perVertex(Reader& r, size_t positions, const char* what) {
  std::vector<T> values = r.array<T>(what);
  if (!values.empty() && values.size() != positions)
    throw Garbled{std::string(what) + ": " + std::to_string(values.size()) + " for " +
                  std::to_string(positions) + " positions"};
  return values;
}

FileContents parseContentsOrThrowGarbled(Reader& r) {
  FileContents contents;
  const size_t images = r.count(8 + 8, "image count");
  for (size_t i = 0; i < images; ++i) {
    const int32_t width = r.get<int32_t>("image width");
    const int32_t height = r.get<int32_t>("image height");
    if (width < 0 || height < 0) throw Garbled{"negative image size"};
    auto pixels = r.array<Vec3f, LargeBlockAllocator<Vec3f>>("image pixels");
    if (pixels.size() != uint64_t(width) * uint64_t(height))
      throw Garbled{"image pixels do not match its size"};
    Image image(width, height);
    image.pixels() = std::move(pixels);
    contents.images.push_back(std::move(image));
  }
  const size_t materials = r.count(8 + 4 * 12 + 8, "material count");
  for (size_t i = 0; i < materials; ++i) {
    FileMaterial m;
    m.material.name = r.string("material name");
    m.material.diffuse = r.get<Vec3f>("material diffuse");
    m.material.diffuseTexture = r.get<int32_t>("material texture");
    m.material.mirror = r.get<Vec3f>("material mirror");
    m.material.emission = r.get<Vec3f>("material emission");
    m.image = indexOrNone(r, contents.images.size(), "material image");
    contents.materials.push_back(std::move(m));
  }
  const size_t parts = r.count(8 + 4 + 2 * sizeof(Mat4) + 4 + 8 + 5 * 8, "part count");
  for (size_t i = 0; i < parts; ++i) {
    FilePart part;
    part.context = r.string("part context");
    part.material = indexOrNone(r, contents.materials.size(), "part material");
    const Mat4 matrix = r.get<Mat4>("part transform");
    const Mat4 inverse = r.get<Mat4>("part transform");
    part.fileFromPart = Transform(matrix, inverse);
    // No node animation is carried (assimp's conversion has none).
    part.node = indexOrNone(r, 0, "part node");
    const size_t names = r.count(8, "part node name count");
    for (size_t k = 0; k < names; ++k) part.nodeNames.push_back(r.string("part node name"));
    part.positions = r.array<Vec3f>("positions");
    part.normals = perVertex<Vec3f>(r, part.positions.size(), "normals");
    part.uvs = perVertex<Vec2f>(r, part.positions.size(), "texture coordinates");
    part.indices = r.array<uint32_t>("indices");
    part.colors = perVertex<Vec3f>(r, part.positions.size(), "colours");
    contents.parts.push_back(std::move(part));
  }
  const size_t warnings = r.count(8, "warning count");
  for (size_t i = 0; i < warnings; ++i) contents.warnings.push_back(r.string("warning"));
  contents.note = r.string("note");
  contents.droppedDegenerate = r.get<uint64_t>("dropped faces");
  const int32_t up = r.get<int32_t>("up axis");
  if (up != int32_t(UpAxis::Auto) && up != int32_t(UpAxis::Y) && up != int32_t(UpAxis::Z) &&
      up != int32_t(UpAxis::MinusY))
    throw Garbled{"up axis " + std::to_string(up)};
  contents.declaredUp = UpAxis(up);
  return contents;
}

// A refusal: the InputError's file, key and whole text (empty file: a message about the
// importer itself).
std::string refusalBlob(const std::string& file, const std::string& key, const std::string& text) {
  Writer w;
  w.put(kMagic);
  w.put(uint32_t(kRefusal));
  w.string(file);
  w.string(key);
  w.string(text);
  w.put(kEndMagic);
  return w.take();
}

// ---- the child ----------------------------------------------------------------------------

// Exit codes of the child besides 0 (its answer is in the memfd).
constexpr int kExitOutOfMemory = 86;
constexpr int kExitSetupFailed = 87;
constexpr int kExitSanitizer = 88;
constexpr int kExitFailed = 89;

constexpr int kResultFd = 3;

[[noreturn]] void outOfMemory() {
  _exit(kExitOutOfMemory);
}

bool writeAll(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes.remove_prefix(size_t(n));
  }
  return true;
}

// The process's address space in bytes (the first figure of /proc/self/statm), 0 if unknown.
uint64_t addressSpaceBytes(pid_t pid = 0) {
  const std::string file = pid ? "/proc/" + std::to_string(pid) + "/statm" : "/proc/self/statm";
  const int fd = open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  char text[128] = {};
  const ssize_t n = read(fd, text, sizeof(text) - 1);
  close(fd);
  if (n <= 0) return 0;
  return std::strtoull(text, nullptr, 10) * uint64_t(sysconf(_SC_PAGESIZE));
}

#ifdef PARALLAX_ASAN
int gReportFd = -1;
// The sanitizer found an error in the child (its report went to the report memfd): the
// child's crash, not the parent's, and no fuzzer's death callback may record it as a finding.
// An allocation the budget refused is "out of memory" to the sanitizer too.
void sanitizerDied() {
  char text[4096] = {};
  const ssize_t n = pread(gReportFd, text, sizeof(text) - 1, 0);
  const std::string_view report(text, n > 0 ? size_t(n) : 0);
  for (const char* oom : {"out of memory", "allocation-size-too-big", "rss-limit-exceeded",
                          "exceeds maximum supported size", "calloc-overflow"})
    if (report.find(oom) != std::string_view::npos) _exit(kExitOutOfMemory);
  _exit(kExitSanitizer);
}
#endif

[[noreturn]] void runChild(int resultFd, int reportFd, const std::string& path,
                           const ImporterLimits& limits,
                           const std::function<FileContents(const std::string&)>& read) {
  (void)reportFd;
  // Default dispositions: a crash ends the child by its signal (the parent names it), and no
  // handler of the parent's (a fuzzer's, a sanitizer's, Python's) runs here.
  for (int s = 1; s < NSIG; ++s)
    if (s != SIGKILL && s != SIGSTOP) signal(s, SIG_DFL);
  signal(SIGPIPE, SIG_IGN);
  signal(SIGXFSZ, SIG_IGN);  // a write beyond RLIMIT_FSIZE fails with EFBIG instead
  sigset_t none;
  sigemptyset(&none);
  sigprocmask(SIG_SETMASK, &none, nullptr);

  // Descriptors: /dev/null for 0-2, the result at 3 (the report at 4), nothing else.
  const int null = open("/dev/null", O_RDWR);
  if (null < 0) _exit(kExitSetupFailed);
  const int highest = std::max({resultFd, reportFd, null});
  // Move the result and report out of the way first, then into place.
  const int result = fcntl(resultFd, F_DUPFD, highest + 1);
  const int report = reportFd >= 0 ? fcntl(reportFd, F_DUPFD, highest + 1) : -1;
  if (result < 0 || dup2(null, 0) < 0 || dup2(null, 1) < 0 || dup2(null, 2) < 0 ||
      dup2(result, kResultFd) != kResultFd)
    _exit(kExitSetupFailed);
  int firstToClose = kResultFd + 1;
  if (report >= 0) {
    if (dup2(report, kResultFd + 1) != kResultFd + 1) _exit(kExitSetupFailed);
    ++firstToClose;
  }
#ifdef SYS_close_range
  if (syscall(SYS_close_range, unsigned(firstToClose), ~0u, 0u) != 0)
#endif
  {
    struct rlimit files;
    const int maxFd = getrlimit(RLIMIT_NOFILE, &files) == 0 && files.rlim_cur != RLIM_INFINITY
                          ? int(std::min<rlim_t>(files.rlim_cur, 1 << 20))
                          : 1 << 16;
    for (int fd = firstToClose; fd < maxFd; ++fd) close(fd);
  }
  // Both descriptors were dup'ed without close-on-exec; nothing execs here anyway.

#ifdef PARALLAX_ASAN
  if (report >= 0) {
    gReportFd = kResultFd + 1;
    __sanitizer_set_report_fd(reinterpret_cast<void*>(intptr_t(gReportFd)));
    __sanitizer_set_death_callback(sanitizerDied);
  }
#endif

  // Limits. Soft CPU limit: SIGXCPU; the hard one a second later: SIGKILL.
  const auto set = [](int resource, rlim_t soft, rlim_t hard) {
    const rlimit limit = {soft, hard};
    return setrlimit(resource, &limit) == 0;
  };
  const rlim_t budget = rlim_t(limits.memoryBytes);
  const uint64_t current = addressSpaceBytes();
  const rlim_t cpu = rlim_t(std::ceil(limits.cpuSeconds));
  if (!set(RLIMIT_CORE, 0, 0) || !set(RLIMIT_CPU, cpu, cpu + 1) ||
      !set(RLIMIT_FSIZE, budget, budget) ||
      (current > 0 && !set(RLIMIT_AS, rlim_t(current) + budget, rlim_t(current) + budget)))
    _exit(kExitSetupFailed);
  std::set_new_handler(outOfMemory);

  if (childFaultForTests) childFaultForTests();

  std::string blob;
  try {
    blob = serializeContents(read(path));
  } catch (const InputError& e) {
    try {
      blob = refusalBlob(e.file(), e.path(), e.what());
    } catch (const std::bad_alloc&) {
      _exit(kExitOutOfMemory);
    }
  } catch (const std::bad_alloc&) {
    _exit(kExitOutOfMemory);
  } catch (const std::exception& e) {
    try {
      blob = serializeRefusal("failed reading it (" + std::string(e.what()) + ")");
    } catch (...) {
      _exit(kExitFailed);
    }
  } catch (...) {
    _exit(kExitFailed);
  }
  if (!writeAll(kResultFd, blob)) _exit(errno == EFBIG ? kExitOutOfMemory : kExitFailed);
  _exit(0);
}

// ---- the parent ---------------------------------------------------------------------------

// A descriptor closed on every path.
struct Fd {
  int fd = -1;
  Fd() = default;
  explicit Fd(int f) : fd(f) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd >= 0) close(fd);
  }
};

// The child is killed and reaped on every path out of readIsolated, exceptions included.
class Child {
 public:
  explicit Child(pid_t pid) : pid_(pid) {}
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (!reaped_) {
      kill(pid_, SIGKILL);
      int status;
      while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
      }
    }
  }
  pid_t pid() const { return pid_; }

  // Non-blocking: true once the child has ended (and is reaped). A SIGCHLD handler or a
  // SIG_IGN disposition elsewhere in the process may reap it first (ECHILD): then the
  // status is unknown and the answer in the memfd decides.
  bool poll() {
    for (;;) {
      const pid_t r = wait4(pid_, &status_, WNOHANG, &usage_);
      if (r == pid_) return reaped_ = known_ = true;
      if (r == 0) return false;
      if (errno == EINTR) continue;
      return reaped_ = true;  // ECHILD
    }
  }
  void killAndReap() {
    kill(pid_, SIGKILL);
    for (;;) {
      const pid_t r = wait4(pid_, &status_, 0, &usage_);
      if (r == pid_) {
        reaped_ = known_ = true;
        return;
      }
      if (r < 0 && errno == EINTR) continue;
      reaped_ = true;
      return;
    }
  }
  bool known() const { return known_; }
  int status() const { return status_; }
  double cpuSeconds() const {
    const auto s = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return s(usage_.ru_utime) + s(usage_.ru_stime);
  }

 private:
  pid_t pid_;
  bool reaped_ = false;
  bool known_ = false;
  int status_ = 0;
  rusage usage_ = {};
};

// The first `size - 1` bytes of /proc/PID/NAME, NUL-terminated in `text`; false if unreadable.
bool readProcFile(pid_t pid, const char* name, char* text, size_t size) {
  const std::string file = "/proc/" + std::to_string(pid) + "/" + name;
  const int fd = open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const ssize_t n = read(fd, text, size - 1);
  close(fd);
  if (n <= 0) return false;
  text[n] = 0;
  return true;
}

// The memory the child has of its own (what it wrote or allocated since the fork, not the
// pages it still shares with the parent), from /proc/PID/smaps_rollup; 0 if unknown.
uint64_t privateBytes(pid_t pid) {
  char text[4096];
  if (!readProcFile(pid, "smaps_rollup", text, sizeof(text))) return 0;
  uint64_t kib = 0;
  for (const char* key : {"Private_Clean:", "Private_Dirty:"})
    if (const char* at = std::strstr(text, key))
      kib += std::strtoull(at + std::strlen(key), nullptr, 10);
  return kib * 1024;
}

// User and system CPU time of a process in clock ticks (/proc/PID/stat), 0 if unknown.
uint64_t cpuTicksOf(pid_t pid) {
  char text[1024];
  if (!readProcFile(pid, "stat", text, sizeof(text))) return 0;
  // After the command name's closing parenthesis: state (field 3) ... utime (14), stime (15).
  const char* at = std::strrchr(text, ')');
  if (!at) return 0;
  char* next = const_cast<char*>(at + 1);
  uint64_t ticks = 0;
  for (int field = 3; field <= 15 && *next; ++field) {
    while (*next == ' ') ++next;
    if (field >= 14)
      ticks += std::strtoull(next, &next, 10);
    else
      while (*next && *next != ' ') ++next;
  }
  return ticks;
}

std::string signalName(int signal) {
  const char* abbrev = sigabbrev_np(signal);
  return "signal " + std::to_string(signal) + (abbrev ? ", SIG" + std::string(abbrev) : "");
}

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", s);
  return text;
}

enum class Ended { ByItself, OverTime, OverMemory };

}  // namespace

std::string serializeContents(const FileContents& contents) {
  // What the flat layout does not carry must be empty (assimp's conversion fills none of it).
  if (!contents.cameras.empty() || !contents.lights.empty() || !contents.nodeAnimation.empty() ||
      !contents.nodeAnimation.nodes.empty())
    throw std::logic_error("serializeContents: cameras, lights and node animation not carried");
  Writer w;
  w.put(kMagic);
  w.put(uint32_t(kContents));
  w.put(uint64_t(contents.images.size()));
  for (const Image& image : contents.images) {
    w.put(int32_t(image.width()));
    w.put(int32_t(image.height()));
    w.array(image.pixels());
  }
  w.put(uint64_t(contents.materials.size()));
  for (const FileMaterial& m : contents.materials) {
    putMaterial(w, m.material);
    w.put(int32_t(m.image));
  }
  w.put(uint64_t(contents.parts.size()));
  for (const FilePart& part : contents.parts) {
    w.string(part.context);
    w.put(int32_t(part.material));
    putTransform(w, part.fileFromPart);
    w.put(int32_t(part.node));
    w.put(uint64_t(part.nodeNames.size()));
    for (const std::string& name : part.nodeNames) w.string(name);
    w.array(part.positions);
    w.array(part.normals);
    w.array(part.uvs);
    w.array(part.indices);
    w.array(part.colors);
  }
  w.put(uint64_t(contents.warnings.size()));
  for (const std::string& warning : contents.warnings) w.string(warning);
  w.string(contents.note);
  w.put(uint64_t(contents.droppedDegenerate));
  w.put(int32_t(contents.declaredUp));
  w.put(kEndMagic);
  return w.take();
}

std::string serializeRefusal(const std::string& message) {
  return refusalBlob("", "", message);
}

FileContents parseContents(std::string_view blob, const std::string& path,
                           const std::string& importer) {
  Reader r(blob);
  try {
    if (r.get<uint64_t>("magic") != kMagic) throw Garbled{"not an answer"};
    const uint32_t kind = r.get<uint32_t>("kind");
    if (kind == kRefusal) {
      std::string file = r.string("file"), key = r.string("key"), text = r.string("message");
      if (r.get<uint64_t>("end") != kEndMagic || !r.atEnd()) throw Garbled{"bytes after the end"};
      if (file.empty()) fail(path, importer + " " + text);
      // The child's InputError as it was: its text without the "file: key: " it begins with.
      const std::string prefix = file + (key.empty() ? "" : ": " + key) + ": ";
      if (text.rfind(prefix, 0) == 0) text.erase(0, prefix.size());
      throw InputError(file, key, text);
    }
    if (kind != kContents) throw Garbled{"kind " + std::to_string(kind)};
    FileContents contents = parseContentsOrThrowGarbled(r);
    if (r.get<uint64_t>("end") != kEndMagic) throw Garbled{"no end mark"};
    if (!r.atEnd()) throw Garbled{"bytes after the end"};
    return contents;
  } catch (const Garbled& g) {
    fail(path, importer + " returned a damaged answer (" + g.what +
                   "); the file is damaged or not supported");
  } catch (const std::bad_alloc&) {
    fail(path, importer + " returned an answer too large for memory");
  }
}

FileContents readIsolated(const std::string& path, const std::string& importer,
                          const std::function<FileContents(const std::string&)>& read) {
  const ImporterLimits limits = importerLimits();
  // The wall clock ends a child that hangs without using CPU (blocked, sleeping, a lock held
  // at the fork): past wallSeconds, one that used no CPU for a second is killed. A child still
  // computing is left to its CPU limit (on a busy machine it gets less than a core), up to
  // 10x the CPU limit.
  const double wallSeconds = 2 * limits.cpuSeconds + 5;
  const double lastWallSeconds = 10 * limits.cpuSeconds + 5;
  const std::string damaged = "; the file is damaged or not supported";

  Fd result(memfd_create("parallax-import", MFD_CLOEXEC));
  if (result.fd < 0) fail(path, "cannot start " + importer + ": " + std::strerror(errno));
  Fd report;
#ifdef PARALLAX_ASAN
  report.fd = memfd_create("parallax-import-report", MFD_CLOEXEC);
#endif

  const pid_t pid = fork();
  if (pid < 0) fail(path, "cannot start " + importer + ": " + std::strerror(errno));
  if (pid == 0) runChild(result.fd, report.fd, path, limits, read);
  Child child(pid);

  // Wait: on a pidfd (woken the moment the child ends), else in short sleeps; every 100 ms
  // the deadline and the child's memory are checked.
  Fd pidfd;
#ifdef SYS_pidfd_open
  pidfd.fd = int(syscall(SYS_pidfd_open, pid, 0));
#endif
  const auto start = std::chrono::steady_clock::now();
  Ended ended = Ended::ByItself;
  int sleepMs = 1;
  uint64_t cpuTicks = 0;
  double lastCpuChange = 0;
  while (!child.poll()) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (const uint64_t ticks = cpuTicksOf(pid); ticks != cpuTicks) {
      cpuTicks = ticks;
      lastCpuChange = elapsed;
    }
    if ((elapsed >= wallSeconds && elapsed - lastCpuChange >= 1) || elapsed >= lastWallSeconds) {
      ended = Ended::OverTime;
      child.killAndReap();
      break;
    }
    if (double(privateBytes(pid)) > limits.memoryBytes) {
      ended = Ended::OverMemory;
      child.killAndReap();
      break;
    }
    const int waitMs = int(std::min(100.0, 1000 * std::max(wallSeconds - elapsed, 0.0) + 1));
    if (pidfd.fd >= 0) {
      pollfd p = {pidfd.fd, POLLIN, 0};
      ::poll(&p, 1, waitMs);  // EINTR: the loop checks again
    } else {
      usleep(useconds_t(1000 * std::min(sleepMs, waitMs)));
      sleepMs = std::min(2 * sleepMs, 50);
    }
  }

  const std::string budget = formatGiB(limits.memoryBytes);
  const std::string ranOut = importer + " ran out of its memory budget reading it (" + budget +
                             ", {max_memory}); the file is damaged or needs a larger {max_memory}";
  const std::string overCpu = importer + " took more than " + seconds(limits.cpuSeconds) +
                              " s of CPU time reading it" + damaged;
  if (ended == Ended::OverTime)
    fail(path, importer + " did not answer within " + seconds(wallSeconds) + " s" + damaged);
  if (ended == Ended::OverMemory) fail(path, ranOut);
  if (child.known()) {
    const int status = child.status();
    if (WIFSIGNALED(status)) {
      const int signal = WTERMSIG(status);
      if (signal == SIGXCPU || (signal == SIGKILL && child.cpuSeconds() >= limits.cpuSeconds))
        fail(path, overCpu);
      fail(path, importer + " crashed reading it (" + signalName(signal) + ")" + damaged);
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
      switch (WEXITSTATUS(status)) {
        case kExitOutOfMemory:
          fail(path, ranOut);
        case kExitSanitizer:
          fail(path,
               importer + " crashed reading it (a memory error the sanitizer caught)" + damaged);
        case kExitSetupFailed:
          fail(path, "cannot start " + importer + " (its process could not be set up)");
        default:
          fail(path, importer + " ended without an answer (exit code " +
                         std::to_string(WEXITSTATUS(status)) + ")" + damaged);
      }
    }
  }

  // The answer. With the status unknown (reaped elsewhere) an incomplete answer says why.
  struct stat info;
  if (fstat(result.fd, &info) != 0 || info.st_size <= 0)
    fail(path, importer + " ended without an answer" + damaged);
  void* mapped = mmap(nullptr, size_t(info.st_size), PROT_READ, MAP_PRIVATE, result.fd, 0);
  if (mapped == MAP_FAILED)
    fail(path, importer + ": cannot read its answer: " + std::strerror(errno));
  struct Unmap {
    void* at;
    size_t size;
    ~Unmap() { munmap(at, size); }
  } unmap{mapped, size_t(info.st_size)};
  return parseContents(std::string_view(static_cast<const char*>(mapped), size_t(info.st_size)),
                       path, importer);
}

}  // namespace meshio
}  // namespace parallax
