#include "kinetic/core/certificate_schedule.h"

#include <algorithm>
#include <cmath>

#include "kinetic/core/certificate_time.h"
#include "kinetic/core/root_finding.h"

namespace kinray::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool broken_at(const OrderCertificate& c, double t) {
  return certificate_sign_after(c, t - c.origin) < 0;
}

// The smallest-found absolute time t >= from with sign_after(f, t - origin) < 0, searching up to
// `limit`; +inf when none. The root r (local) is known to have sign_after(f, r) < 0, but
// origin + r rounds, and t - origin is what the handler will evaluate.
double nudge(const OrderCertificate& c, double from, double limit) {
  double t = from;
  for (int k = 0; k < 16; ++k) {
    if (broken_at(c, t)) return t;
    t = std::nextafter(t, kInf);
  }
  // Wider noise band: gallop, then bisect back to the first broken time found.
  double lo = t, step = std::max(std::fabs(t), 1e-300) * 0x1p-50;
  while (true) {
    const double hi = lo + step;
    if (!(hi <= limit) || !std::isfinite(hi)) return kInf;
    if (broken_at(c, hi)) {
      double good = lo, bad = hi;
      while (std::nextafter(good, kInf) < bad) {
        const double m = good + 0.5 * (bad - good);
        if (m <= good || m >= bad) break;
        (broken_at(c, m) ? bad : good) = m;
      }
      return bad;
    }
    lo = hi;
    step *= 2;
  }
}

// The recheck of a certificate decided exactly (schedule_certificate's defer_exact): the last
// absolute time t > now whose local time t - origin (as the handler computes it) is at most
// `until`, before which the filter that sent c to the exact path saw F hold. Nothing without
// that vouch, or when no such time lies after now: the exact search decides then. (The exact
// polynomial's own, tighter envelope would vouch for longer, but its failure lies in F's noise
// band, where an exact search that starts there costs some hundred times one started before it.)
std::optional<double> exact_recheck_time(const OrderCertificate& c, double now, double s_now) {
  if (!(c.vouched.orientation > 0 && c.vouched.covers(s_now))) return std::nullopt;
  double t = c.origin + c.vouched.until;
  while (t - c.origin > c.vouched.until) t = std::nextafter(t, -kInf);
  if (!(t > now)) return std::nullopt;
  return t;
}

}  // namespace

int certificate_sign_after(const OrderCertificate& c, double s) {
  if (!c.exact) return sign_after(c.f, s);
  if (c.vouched.covers(s)) return c.vouched.orientation;  // the exact polynomial is not asked
  return exact_sign_after(*c.exact, s);
}

int order_sign(const OrderCertificate& c, double now, uint32_t a, uint32_t b) {
  const int s = certificate_sign_after(c, now - c.origin);
  if (s != 0) return s;
  return a < b ? 1 : (a > b ? -1 : 1);
}

Schedule schedule_certificate(const OrderCertificate& c, double now, uint32_t a, uint32_t b,
                              bool defer_exact) {
  Schedule s;
  const double s_now = now - c.origin;
  if (c.f.is_zero() && (!c.exact || exact_sign_after(*c.exact, s_now) == 0)) {
    if (a > b) {
      s.time = now;
      s.failure = true;
    } else if (c.end < kInf && c.end > now) {
      s.time = c.end;
    }
    return s;
  }
  if (c.exact && defer_exact) {
    if (const std::optional<double> t = exact_recheck_time(c, now, s_now)) {
      s.time = *t;
      s.recheck = true;
      return s;
    }
  }
  // holds_through decides only where first_failure would find no failure (the same answer); a
  // positive constant (a pixel order's pair apart in depth) is what it decides first, read here
  // without its margins: its margin is 16 eps |c0|.
  const double s_end = c.end - c.origin;
  const bool positive_constant = !c.exact && c.f.degree == 0 && c.f.c[0] > 0 &&
                                 std::isfinite(c.f.c[0]) && std::isfinite(s_now) &&
                                 std::isfinite(s_end) && s_end >= s_now;
  const auto r = c.exact ? exact_first_failure(*c.exact, s_now, s_end)
                 : positive_constant || holds_through(c.f, s_now, s_end)
                     ? std::nullopt
                     : first_failure(c.f, s_now, s_end);
  if (!r) {
    // Renewal at the end of validity. A certificate that ends at (or before) now is stale: the
    // keys have not switched to the next motion yet, and renewing at now would loop; the owner
    // calls replace_motion once the motion is updated.
    if (c.end < kInf && c.end > now) s.time = c.end;
    return s;
  }
  s.failure = true;
  if (*r == s_now) {
    s.time = now;
    return s;
  }
  const double t = std::max(now, c.origin + *r);
  const double limit = c.end < kInf ? c.end + std::max(1.0, std::fabs(c.end)) * 1e-9
                                    : t + std::max(1.0, std::fabs(t)) * 1e-6;
  s.time = nudge(c, t, limit);
  if (s.time == kInf) {
    // The dip below zero is not representable in absolute time: a touch within rounding.
    s.failure = false;
    s.degenerate = true;
    if (c.end < kInf && c.end > now) s.time = c.end;
  }
  return s;
}

Schedule schedule_degenerate(const OrderCertificate& c, double now, uint32_t a, uint32_t b) {
  Schedule s;
  s.degenerate = true;
  const double s_now = now - c.origin, s_end = c.end - c.origin;
  double back = kInf;  // first - to + change
  if (!c.f.is_zero()) {
    for (double x : sign_changes(c.f, s_now, s_end)) {
      if (sign_after(c.f, x) > 0) {
        back = x;
        break;
      }
    }
  }
  if (back == kInf) {
    s.broken_until = c.end;
    if (c.end < kInf && c.end > now) s.time = c.end;
    return s;
  }
  s.broken_until = c.origin + back;
  OrderCertificate later = c;
  Schedule next = schedule_certificate(later, std::max(now, std::nextafter(s.broken_until, kInf)),
                                       a, b);
  next.degenerate = true;
  next.broken_until = s.broken_until;
  if (next.time < now) next.time = now;
  return next;
}

}  // namespace kinray::detail
