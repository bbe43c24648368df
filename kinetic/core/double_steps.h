#pragma once
// Stepping through doubles to pin down the first one where a sign test holds: the last stage of
// the failure-time searches of root_finding.cpp and certificate_time.cpp, which must land on the
// same double as the callers' own evaluation (docs/design.md, "Root isolation and its filters").
#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <optional>

namespace kinray::detail {

/// std::nextafter(x, +inf) for finite x, without the libm call.
inline double next_up(double x) {
  if (x == 0) return std::numeric_limits<double>::denorm_min();
  const auto b = std::bit_cast<uint64_t>(x);
  return std::bit_cast<double>(x > 0 ? b + 1 : b - 1);
}
/// std::nextafter(x, -inf) for finite x.
inline double next_down(double x) { return -next_up(-x); }

/// A point strictly between lo < hi (adjacent doubles excluded by the caller): bisection in the
/// ordered bit space, so that any bracket shrinks to adjacent doubles in at most 64 steps.
inline double bit_midpoint(double lo, double hi) {
  if (lo < 0 && hi > 0) return 0.0;
  if (lo >= 0) {
    const auto a = std::bit_cast<uint64_t>(lo == 0 ? 0.0 : lo), b = std::bit_cast<uint64_t>(hi);
    return std::bit_cast<double>(a + (b - a) / 2);
  }
  return -bit_midpoint(-hi, -lo);
}

/// The first double r in (s_now, top] with negative(r), where negative switches once from false
/// to true near the guess g (s_now < g <= top, negative(s_now) false): gallops from g with steps
/// doubling from `step` to a bracket, then bisects it to adjacent doubles. std::nullopt when the
/// upward gallop reaches top without negative, or needs more than `max_tries` steps (the caller
/// then falls back to a general search). `refinements` counts the bisection steps.
template <class Negative>
[[nodiscard]] std::optional<double> first_negative_near(Negative&& negative, double g, double s_now,
                                                        double top, double step, int max_tries,
                                                        uint64_t* refinements = nullptr) {
  double lo, hi;
  if (negative(g)) {
    hi = g;
    lo = next_down(g);
    while (lo > s_now && negative(lo)) {
      hi = lo;
      lo = std::max(s_now, lo - step);
      step *= 2;
    }
    lo = std::max(lo, s_now);
  } else {
    lo = g;
    hi = next_up(g);
    for (int tries = 0; !negative(hi);) {
      if (hi >= top || ++tries > max_tries) return std::nullopt;
      lo = hi;
      hi = std::min(top, hi + step);
      step *= 2;
    }
  }
  while (next_up(lo) < hi) {
    if (refinements) ++*refinements;
    const double m = bit_midpoint(lo, hi);
    (negative(m) ? hi : lo) = m;
  }
  return hi;
}

}  // namespace kinray::detail
