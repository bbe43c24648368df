#include "kinetic/core/certificate_time.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinetic/core/certificate_schedule.h"
#include "kinetic/core/double_steps.h"
#include "kinetic/core/root_finding.h"

namespace kinray {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using detail::next_up;

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// Horner's rule on c[0..N], highest first.
template <int N>
double horner(const double* c, double s) {
  double acc = c[N];
  for (int k = N - 1; k >= 0; --k) acc = acc * s + c[k];
  return acc;
}

/// Exact f (coefficients c[0..N]) exceeds 8 N eps (|c0| + |c1| S + ... + |cN| S^N) (S = max |s|)
/// at both ends of [a, b]: then Horner's value there, and wherever exact f is at least as large,
/// is positive (its error is at most gamma_2N times that sum, with or without fused
/// multiply-adds; the factor 2 covers the rounding of the bound itself).
template <int N>
bool ends_clear(const double* c, double a, double b, double big_s) {
  double scale = 0;
  for (int k = N; k >= 0; --k) scale = scale * big_s + std::fabs(c[k]);
  const double margin = 16 * double(std::max(N, 1)) * kEps * scale;
  return std::isfinite(margin) && horner<N>(c, a) > margin && horner<N>(c, b) > margin;
}

/// ends_clear, and the minimum of f on the window is at an end: f is linear, opens downwards, or
/// its slope passes the same test with one sign. The slope's coefficients k c_k are rounded
/// (3 c_3), by far less than the margin it is then certified with.
template <int N>
bool clear_through(const double* c, double a, double b, double big_s) {
  if (!ends_clear<N>(c, a, b, big_s)) return false;
  if constexpr (N <= 1) {
    return true;
  } else {
    if (N == 2 && c[2] < 0) return true;
    double slope[N], minus[N];
    for (int k = 1; k <= N; ++k) {
      slope[k - 1] = double(k) * c[k];
      minus[k - 1] = -slope[k - 1];
    }
    return clear_through<N - 1>(slope, a, b, big_s) || clear_through<N - 1>(minus, a, b, big_s);
  }
}

/// Interval Horner over [a, b] (0 <= a <= b): the lower end of an enclosure of f's range there
/// exceeds twice ends_clear's margin. Rounding moves the computed end by at most what it moves
/// Horner's value (gamma_2N times the same magnitudes), so exact f exceeds the margin throughout
/// and Horner's value is positive at every double of the window. It decides the windows
/// clear_through cannot, a minimum inside the window far above zero, as the depth certificates
/// of a pixel order have where two surfaces are far apart and their distance turns.
template <int N>
bool range_clear(const double* c, double a, double b, double big_s) {
  if (!(a >= 0)) return false;
  double scale = 0, lo = c[N], hi = c[N];
  for (int k = N; k >= 0; --k) scale = scale * big_s + std::fabs(c[k]);
  for (int k = N - 1; k >= 0; --k) {
    const double l = lo >= 0 ? lo * a : lo * b, h = hi >= 0 ? hi * b : hi * a;
    lo = l + c[k];
    hi = h + c[k];
  }
  const double margin = 16 * double(N) * kEps * scale;
  return std::isfinite(margin) && lo > 2 * margin;
}

using detail::Quadratic;

/// The closed-form root is within a few units in the last place of the first failing double
/// wherever the quadratic is well conditioned: the search for that double starts with steps of
/// a sixteenth of the slack (four to eight ulps), doubling, rather than the whole slack, and so
/// bisects a bracket of a few ulps. The same double either way (the sign switches once there).
constexpr double kFirstStep = 1.0 / 16;

/// first_failure_low_degree's closed-form path (c2 != 0) step for step, on Quadratic's
/// operations; at_now = q(s_now).
std::optional<double> first_failure_quadratic(const Quadratic& q, double at_now, double s_now,
                                              double s_end) {
  if (q.sign_after(s_now, at_now) < 0) return s_now;
  if (!(s_end > s_now)) return std::nullopt;
  auto negative = [&](double s) { return q.sign_after(s) < 0; };
  const double c0 = q.c0, c1 = q.c1, c2 = q.c2;
  const long double disc = (long double)c1 * c1 - 4.0L * (long double)c2 * c0;
  if (disc <= 0) {
    const double vertex = -c1 / (2 * c2);
    if (vertex > s_now && vertex <= s_end && negative(vertex))
      return first_failure(q.polynomial(), s_now, s_end);
    return std::nullopt;
  }
  const double root = double(std::sqrt(disc));
  const double h = -0.5 * (c1 + std::copysign(root, c1));
  const double r1 = h / c2, r2 = c0 / h;
  const double r = c2 > 0 ? std::min(r1, r2) : std::max(r1, r2);
  if (!std::isfinite(r)) return first_failure(q.polynomial(), s_now, s_end);
  const double slack = 64 * kEps * std::max({std::fabs(r), std::fabs(s_now), 1e-300});
  if (r < s_now - slack) return std::nullopt;
  if (r > s_end + slack) return std::nullopt;
  const double g = std::clamp(r, next_up(s_now), s_end);
  const std::optional<double> t =
      detail::first_negative_near(negative, g, s_now, s_end, kFirstStep * slack, 24);
  return t ? t : first_failure(q.polynomial(), s_now, s_end);
}

/// The absolute time of the first failure after `now`, from the local one r (first_failure's
/// answer): the first double from origin + r on where `negative` holds, as the event handler
/// will evaluate it (the subtraction t - origin in double); past 16 of them the general schedule
/// of the certificate (`polynomial()`, built only then) decides.
template <class Negative, class MakePolynomial>
double absolute_failure_time(std::optional<double> r, Negative&& negative,
                             MakePolynomial&& polynomial, double origin, double now, double end) {
  if (!r) return kInf;
  if (*r == now - origin) return now;
  double t = std::max(now, origin + *r);
  for (int k = 0; k < 16; ++k, t = next_up(t))
    if (negative(t - origin)) return t;
  // The dip is not representable near the root in absolute time: the general schedule decides.
  OrderCertificate c;
  c.f = polynomial();
  c.origin = origin;
  c.end = end;
  const detail::Schedule s = detail::schedule_certificate(c, now, 0, 0);
  return s.failure ? s.time : kInf;
}

}  // namespace

// Out of line (quadratic_failure_time, inline, runs the filter): the same arithmetic as the
// general path, so the same time (test CertificateTime.*).
double detail::undecided_quadratic_failure_time(const Quadratic& q, double at_now, double origin,
                                                double now, double end) {
  const double s_now = now - origin, s_end = end - origin;
  const std::optional<double> r = q.c2 != 0
                                      ? first_failure_quadratic(q, at_now, s_now, s_end)
                                      : first_failure_low_degree(q.polynomial(), s_now, s_end);
  return absolute_failure_time(
      r, [&](double s) { return q.sign_after(s) < 0; }, [&] { return q.polynomial(); }, origin, now,
      end);
}

bool holds_through(const Polynomial& f, double s_now, double s_end) {
  if (!(std::isfinite(s_now) && std::isfinite(s_end) && s_end >= s_now)) return false;
  const double big_s = std::max(std::fabs(s_now), std::fabs(s_end));
  switch (f.degree) {
    case 0:
    case 1: return clear_through<1>(f.c.data(), s_now, s_end, big_s);
    case 2: return clear_through<2>(f.c.data(), s_now, s_end, big_s);
    case 3: return clear_through<3>(f.c.data(), s_now, s_end, big_s);
    case 4:
      return range_clear<4>(f.c.data(), s_now, s_end, big_s) ||
             clear_through<4>(f.c.data(), s_now, s_end, big_s);
    case 5:
      return range_clear<5>(f.c.data(), s_now, s_end, big_s) ||
             clear_through<5>(f.c.data(), s_now, s_end, big_s);
    default: return false;
  }
}

bool holds_from_root(const Polynomial& f, double s_now, double s_end) {
  // first_failure isolates on [s_now, s_end] (no tail beyond 2^100), on f scaled by a power of
  // two, which must stay exact; 16 u |c_k| below must not underflow.
  if (!(f.degree == 3 && f.c[3] != 0 && s_now >= 0 && s_end > s_now && s_end <= 0x1p100))
    return false;
  if (sign_after(f, s_now) <= 0 || sign_after(f, s_end) <= 0) return false;
  const double largest =
      std::max({std::fabs(f.c[0]), std::fabs(f.c[1]), std::fabs(f.c[2]), std::fabs(f.c[3])});
  // d = f + 16 u |f| coefficient-wise, rounded: d_k <= c_k + 17.1 u |c_k|, so that for s >= 0,
  // d(s) <= f(s) + 17.1 u M(s), M(s) = sum |c_k| s^k.
  Polynomial d;
  d.degree = 3;
  for (int k = 0; k <= 3; ++k) {
    const double c = f.c[size_t(k)], a = std::fabs(c);
    if (a != 0 && (a < 0x1p-900 || a < largest * 0x1p-900)) return false;
    d.c[size_t(k)] = c + 0x1p-49 * a;
  }
  // d(s_now) > 0: Horner's value clears its error (gamma_6 of the magnitudes, below 8 u).
  const double mag =
      ((std::fabs(d.c[3]) * s_now + std::fabs(d.c[2])) * s_now + std::fabs(d.c[1])) * s_now +
      std::fabs(d.c[0]);
  if (!(d(s_now) > 0x1p-50 * mag)) return false;
  // and rises on [s_now, top] (top >= s_end (1 + u) covers the leaves' rounded ends), or rises
  // on its first eighth and clears holds_through's margin on the rest.
  const double top = next_up(next_up(s_end));
  const Polynomial slope = d.derivative();
  if (holds_through(slope, s_now, top)) return true;
  const double mid = s_now + (top - s_now) / 8;
  return holds_through(slope, s_now, mid) && holds_through(d, mid, top);
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
  const std::optional<double> t =
      detail::first_negative_near(negative, g, s_now, s_end, kFirstStep * slack, 24);
  return t ? t : first_failure(f, s_now, s_end);
}

double certificate_failure_time(const Polynomial& f, double origin, double now, double end) {
  return certificate_failure_time(1, f, origin, now, end);
}

double certificate_failure_time(int sign, const Polynomial& f, double origin, double now,
                                double end) {
  if (f.degree == 2) return quadratic_failure_time(sign, f.c[0], f.c[1], f.c[2], origin, now, end);
  const Polynomial g = sign > 0 ? f : -f;
  const double s_now = now - origin;
  if (holds_through(g, s_now, end - origin) || holds_from_root(g, s_now, end - origin)) return kInf;
  return absolute_failure_time(
      first_failure_low_degree(g, s_now, end - origin),
      [&](double s) { return sign_after(g, s) < 0; }, [&] { return g; }, origin, now, end);
}

}  // namespace kinray
