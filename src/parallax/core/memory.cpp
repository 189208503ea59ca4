#include "parallax/core/memory.h"

#include <sys/resource.h>

namespace parallax {

double peakResidentMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

}  // namespace parallax
