#pragma once
// Wall time for the stats and the benchmarks, on the steady clock, in seconds.
#include <chrono>

namespace kinray {

/// Seconds from `start` to now.
[[nodiscard]] inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Seconds from `since` to now, and `since` moved to now: the consecutive laps of one clock.
inline double lap_seconds(std::chrono::steady_clock::time_point& since) {
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - since).count();
  since = now;
  return seconds;
}

}  // namespace kinray
