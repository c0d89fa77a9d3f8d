#pragma once
// Milliseconds on the steady clock since a start: the stage timings every stats() reports.
#include <chrono>

namespace tvf {

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace tvf
