// Process memory figures for benchmarks, and the estimates that keep a command from allocating
// more than the machine has (docs/inputs.md): a command adds up what it will allocate before it
// allocates it and checks the sum against a limit (by default 3/4 of physical memory).
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace parallax {

// Peak resident set size of this process so far, in MiB (from getrusage).
double peakResidentMiB();
// The same in bytes, or the peak of a finished child process (a sandboxed importer) when that
// was higher: what `/usr/bin/time -v` reports as the maximum resident set size.
double peakResidentBytes();
// Resident set size of this process now, in bytes (/proc/self/statm); 0 when unknown. What a
// command holds before its work: the program, its libraries, Embree's and oneTBB's own memory,
// the loaded scene and pictures.
double residentBytes();
// Hands the heap's free pages back to the system (glibc's malloc_trim), so that residentBytes()
// counts what is held rather than what was freed after loading (a parser's temporaries), which
// later allocations may or may not reuse.
void releaseFreeMemory();

inline constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

// Bytes per pixel of the program's float RGB images (parallax::Image: three floats).
inline constexpr double kFloatRgbPixelBytes = 12.0;
// Bytes per pixel of an 8-bit RGBA picture (the PNG writer's buffer, an upper bound).
inline constexpr double kRgba8PixelBytes = 4.0;
// Bytes per pixel of 8-bit RGB codes (a PNG's samples, its encoder's filtered rows).
inline constexpr double kRgb8PixelBytes = 3.0;

// Physical memory of the machine in bytes (sysconf), lowered to the cgroup's memory.max when a
// container sets one; 0 when unknown.
uint64_t physicalMemoryBytes();

// Seconds of the fastest of three reads of `bytes` bytes (on `threads` workers, 0: all cores, each
// reading blocks of 1 MiB from memory, not cache): what one pass over that many bytes costs at
// this machine's memory bandwidth (the layer solvers' limit in `parallax bench --layers`). Here,
// in a library compiled with the build's optimisation, so that the reads are as fast as the
// solvers' own.
double streamingPassSeconds(double bytes, int threads);

// 3/4 of `physicalBytes` (the rest is left to the system and other programs); 4 GiB when the
// physical memory is unknown (0).
double defaultMemoryLimitBytes(uint64_t physicalBytes);

// Bytes of `count` pictures of width x height pixels of `bytesPerPixel` each, as a double (no
// overflow for any int sizes).
double imageBytes(double width, double height, double bytesPerPixel = kFloatRgbPixelBytes,
                  double count = 1.0);

// "51 GiB", "2.5 GiB", "0.04 GiB": bytes in GiB with two significant digits below 10.
std::string formatGiB(double bytes);

// The refusal when `bytes` exceed `limitBytes`: throws InputError(subject, "", "needs about
// X GiB for WHAT (limit Y GiB); ADVICE"). `subject` is the option that asked for it with its
// value ("--size 65536x65536").
void checkMemory(double bytes, double limitBytes, const std::string& subject,
                 const std::string& what, const std::string& advice);

// Buffers of whole images (pixels, a solver's targets) are written once right after they are
// allocated, and at the sizes this program works at (25 MB a 1080p picture, a GB of training
// targets) the kernel's page faults on that first touch cost seconds in 4 KiB pages (a sixth of a
// 1080p layer solve's time was page faults; measured in docs/content-adaptive.md, "Cost").
// Blocks of kLargeBlockBytes and more are therefore aligned to 2 MiB and marked
// MADV_HUGEPAGE before they are touched, so that a kernel whose transparent huge pages are
// "madvise" (Debian's default) backs them with 2 MiB pages: one fault where there were 512.
// Smaller blocks come from operator new as usual. No effect on any result.
inline constexpr size_t kLargeBlockBytes = size_t(4) << 20;
void* allocateBlock(size_t bytes);
void freeBlock(void* block, size_t bytes);

// While one of these lives, large blocks freed are kept (64 MiB of them at most) for the next
// allocation of the same size instead of going back to the kernel, which would hand them out
// again zeroed page by page: a layer solve's per-eye pictures and per-iteration images come
// and go at a few sizes (measured in docs/content-adaptive.md, "Cost"). Scoped, because kept
// blocks of sizes that never come again raise a command's peak (a supersampled film): the
// last one to go releases what is kept.
// What is kept now, in bytes.
size_t keptBlockBytes();
class KeepFreedBlocks {
 public:
  KeepFreedBlocks();
  ~KeepFreedBlocks();
  KeepFreedBlocks(const KeepFreedBlocks&) = delete;
  KeepFreedBlocks& operator=(const KeepFreedBlocks&) = delete;
};

template <class T>
struct LargeBlockAllocator {
  using value_type = T;
  LargeBlockAllocator() = default;
  template <class U>
  LargeBlockAllocator(const LargeBlockAllocator<U>&) {}
  T* allocate(size_t count) { return static_cast<T*>(allocateBlock(count * sizeof(T))); }
  void deallocate(T* block, size_t count) { freeBlock(block, count * sizeof(T)); }
  template <class U>
  bool operator==(const LargeBlockAllocator<U>&) const {
    return true;
  }
};

// A vector for whole images' worth of values.
template <class T>
using LargeVector = std::vector<T, LargeBlockAllocator<T>>;

// The same blocks, but a value made without arguments (`resize(n)`, `vector(n)`) is
// default-initialised: floats and codes are not written. For buffers that their owner fills
// whole right away in parallel: the first touch of their pages, the kernel zeroing them, then
// happens on every core instead of on the one that sized them (in a virtual machine that
// first touch is slow: docs/content-adaptive.md, "Cost").
template <class T>
struct UninitializedLargeBlockAllocator : LargeBlockAllocator<T> {
  UninitializedLargeBlockAllocator() = default;
  template <class U>
  UninitializedLargeBlockAllocator(const UninitializedLargeBlockAllocator<U>&) {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <class T>
using UninitializedLargeVector = std::vector<T, UninitializedLargeBlockAllocator<T>>;

}  // namespace parallax
