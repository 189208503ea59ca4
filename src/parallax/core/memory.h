// Process memory figures for benchmarks.
#pragma once

namespace parallax {

// Peak resident set size of this process so far, in MiB (from getrusage).
double peakResidentMiB();

}  // namespace parallax
