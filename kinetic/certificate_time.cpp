#include "kinetic/certificate_time.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>

#include "kinetic/kinetic_sort.h"
#include "kinetic/root_finding.h"

namespace kinray {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double next_up(double x) { return std::nextafter(x, kInf); }
double next_down(double x) { return std::nextafter(x, -kInf); }

// A point strictly between lo < hi that halves the bracket in the ordered bit space, so that a
// bisection ends on adjacent doubles within 64 steps.
double bit_midpoint(double lo, double hi) {
  if (lo < 0 && hi > 0) return 0.0;
  if (lo >= 0) {
    const auto a = std::bit_cast<uint64_t>(lo == 0 ? 0.0 : lo), b = std::bit_cast<uint64_t>(hi);
    return std::bit_cast<double>(a + (b - a) / 2);
  }
  return -bit_midpoint(-hi, -lo);
}

}  // namespace

std::optional<double> first_failure_low_degree(const Polynomial& f, double s_now, double s_end) {
  if (f.effective_degree() != 2) return first_failure(f, s_now, s_end);
  if (sign_after(f, s_now) < 0) return s_now;
  if (!(s_end > s_now)) return std::nullopt;
  auto negative = [&](double s) { return sign_after(f, s) < 0; };
  const double c0 = f.c[0], c1 = f.c[1], c2 = f.c[2];
  // The discriminant in extended precision: it decides between a crossing and a touch.
  const long double disc = (long double)c1 * c1 - 4.0L * (long double)c2 * c0;
  if (disc <= 0) {
    // No crossing in exact arithmetic; a double root may still dip below zero in Horner's
    // values at its vertex, and then the general path decides.
    const double vertex = -c1 / (2 * c2);
    if (vertex > s_now && vertex <= s_end && negative(vertex)) return first_failure(f, s_now, s_end);
    return std::nullopt;
  }
  const double root = double(std::sqrt(disc));
  const double q = -0.5 * (c1 + std::copysign(root, c1));
  const double r1 = q / c2, r2 = c0 / q;
  // f goes from + to - at the smaller root when it opens upwards, at the larger one otherwise.
  const double r = c2 > 0 ? std::min(r1, r2) : std::max(r1, r2);
  if (!std::isfinite(r)) return first_failure(f, s_now, s_end);
  const double slack = 64 * std::numeric_limits<double>::epsilon() * std::max({std::fabs(r), std::fabs(s_now), 1e-300});
  if (r < s_now - slack) return std::nullopt;  // the crossing is behind us
  if (r > s_end + slack) return std::nullopt;  // beyond the segment
  // Bracket [lo, hi]: lo not negative (s_now is positive just after), hi negative.
  double g = std::clamp(r, next_up(s_now), s_end);
  double lo, hi;
  if (negative(g)) {
    hi = g;
    lo = next_down(g);
    double step = slack;
    while (lo > s_now && negative(lo)) {
      hi = lo;
      lo = std::max(s_now, lo - step);
      step *= 2;
    }
    lo = std::max(lo, s_now);
  } else {
    lo = g;
    hi = next_up(g);
    double step = slack;
    int tries = 0;
    while (!negative(hi)) {
      if (hi >= s_end || ++tries > 24) return first_failure(f, s_now, s_end);
      lo = hi;
      hi = std::min(s_end, hi + step);
      step *= 2;
    }
  }
  while (next_up(lo) < hi) {
    const double m = bit_midpoint(lo, hi);
    (negative(m) ? hi : lo) = m;
  }
  return hi;
}

double certificate_failure_time(const Polynomial& f, double origin, double now, double end) {
  const double s_now = now - origin;
  const std::optional<double> r = first_failure_low_degree(f, s_now, end - origin);
  if (!r) return kInf;
  if (*r == s_now) return now;
  double t = std::max(now, origin + *r);
  for (int k = 0; k < 16; ++k, t = next_up(t))
    if (sign_after(f, t - origin) < 0) return t;
  // The dip is not representable near the root in absolute time: the general schedule decides.
  OrderCertificate c;
  c.f = f;
  c.origin = origin;
  c.end = end;
  const detail::Schedule s = detail::schedule_certificate(c, now, 0, 0);
  return s.failure ? s.time : kInf;
}

}  // namespace kinray
