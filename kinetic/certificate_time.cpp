#include "kinetic/certificate_time.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinetic/double_steps.h"
#include "kinetic/kinetic_sort.h"
#include "kinetic/root_finding.h"

namespace kinray {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using detail::next_up;

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// Horner's rule on c[0..n], highest first.
double horner(const double* c, int n, double s) {
  double acc = c[n];
  for (int k = n - 1; k >= 0; --k) acc = acc * s + c[k];
  return acc;
}

/// Exact f (coefficients c[0..n], n <= 3) exceeds 8 n eps (|c0| + |c1| S + ... + |cn| S^n)
/// (S = max |s|) at both ends of [a, b]: then Horner's value there, and wherever exact f is at
/// least as large, is positive (its error is at most gamma_2n times that sum, with or without
/// fused multiply-adds; the factor 2 covers the rounding of the bound itself). And the minimum
/// of f on the window is at an end: it is linear, opens downwards (n = 2), or its slope passes
/// the same test with one sign. The slope's coefficients k c_k are rounded (3 c_3), by far less
/// than the margin it is certified with.
bool clear_through(const double* c, int n, double a, double b, double big_s) {
  double scale = 0;
  for (int k = n; k >= 0; --k) scale = scale * big_s + std::fabs(c[k]);
  const double margin = 16 * double(std::max(n, 1)) * kEps * scale;
  if (!(std::isfinite(margin) && horner(c, n, a) > margin && horner(c, n, b) > margin)) return false;
  if (n <= 1 || (n == 2 && c[2] < 0)) return true;
  double slope[3], minus[3];
  for (int k = 1; k <= n; ++k) {
    slope[k - 1] = double(k) * c[k];
    minus[k - 1] = -slope[k - 1];
  }
  return clear_through(slope, n - 1, a, b, big_s) || clear_through(minus, n - 1, a, b, big_s);
}

}  // namespace

bool holds_through(const Polynomial& f, double s_now, double s_end) {
  return f.degree <= 3 && std::isfinite(s_now) && std::isfinite(s_end) && s_end >= s_now &&
         clear_through(f.c.data(), f.degree, s_now, s_end, std::max(std::fabs(s_now), std::fabs(s_end)));
}

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
  // From the rounded root to the first double where f is negative, as Horner's values say.
  const double g = std::clamp(r, next_up(s_now), s_end);
  const std::optional<double> t = detail::first_negative_near(negative, g, s_now, s_end, slack, 24);
  return t ? t : first_failure(f, s_now, s_end);
}

double certificate_failure_time(const Polynomial& f, double origin, double now, double end) {
  const double s_now = now - origin;
  if (holds_through(f, s_now, end - origin)) return kInf;
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
