// Wall-clock seconds for the timings that reports and logs give.
#pragma once

#include <chrono>

namespace hexdom {

/// Seconds of steady (monotonic) time from `start` to now; never negative.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace hexdom
