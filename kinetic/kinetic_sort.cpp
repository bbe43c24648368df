#include "kinetic/kinetic_sort.h"

#include <algorithm>
#include <cmath>

#include "kinetic/certificate_time.h"

namespace kinray {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

QualityCounts quality_counts(const KineticSortStats& s, size_t objects) {
  QualityCounts q;
  q.certificates_live_max = s.certificates_live;
  q.certificates_live = s.certificates_live;
  q.certificates_computed = s.work;
  q.events = s.events() + s.events_renewal;
  q.events_internal = s.events_internal;
  q.events_external = s.events_external;
  q.objects_present = objects;
  return q;
}

namespace detail {

namespace {

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
}  // namespace

int certificate_sign_after(const OrderCertificate& c, double s) {
  return c.exact ? exact_sign_after(*c.exact, s) : sign_after(c.f, s);
}

int order_sign(const OrderCertificate& c, double now, uint32_t a, uint32_t b) {
  const int s = certificate_sign_after(c, now - c.origin);
  if (s != 0) return s;
  return a < b ? 1 : (a > b ? -1 : 1);
}

Schedule schedule_certificate(const OrderCertificate& c, double now, uint32_t a, uint32_t b) {
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
  // holds_through decides only where first_failure would find no failure (the same answer).
  const auto r = c.exact ? exact_first_failure(*c.exact, s_now, c.end - c.origin)
                 : holds_through(c.f, s_now, c.end - c.origin)
                     ? std::nullopt
                     : first_failure(c.f, s_now, c.end - c.origin);
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

double value_tolerance(double va, double vb) {
  return 1e-9 * (1 + std::fabs(va) + std::fabs(vb));
}

}  // namespace detail

uint32_t PolynomialKeys::add(const Polynomial& p, double start) {
  m_objects.push_back({Segment{start, p}});
  return static_cast<uint32_t>(m_objects.size() - 1);
}

uint32_t PolynomialKeys::add_copy(uint32_t other) {
  m_objects.push_back(m_objects.at(other));
  return static_cast<uint32_t>(m_objects.size() - 1);
}

void PolynomialKeys::set_motion(uint32_t id, const Polynomial& p, double start) {
  auto& segs = m_objects.at(id);
  while (!segs.empty() && segs.back().start >= start) segs.pop_back();
  segs.push_back({start, p});
}

void PolynomialKeys::append_motion(uint32_t id, const Polynomial& p, double start) {
  auto& segs = m_objects.at(id);
  KINRAY_CHECK(segs.empty() || start > segs.back().start);
  segs.push_back({start, p});
}

PolynomialKeys::Active PolynomialKeys::active(uint32_t id, double t) const {
  const auto& segs = m_objects[id];
  KINRAY_DCHECK(!segs.empty());
  // Segment k is active on [start_k, start_{k+1}); "valid from t on" picks the new one at a start.
  size_t k = 0;
  while (k + 1 < segs.size() && segs[k + 1].start <= t) ++k;
  return {&segs[k], k + 1 < segs.size() ? segs[k + 1].start : kInf};
}

OrderCertificate PolynomialKeys::order_certificate(uint32_t a, uint32_t b, double t) const {
  const Active A = active(a, t), B = active(b, t);
  OrderCertificate c;
  c.origin = std::max(A.seg->start, B.seg->start);
  const Polynomial fa = shifted(A.seg->p, c.origin - A.seg->start);
  const Polynomial fb = shifted(B.seg->p, c.origin - B.seg->start);
  c.f = fb - fa;
  c.end = std::min(A.next_start, B.next_start);
  return c;
}

double PolynomialKeys::value(uint32_t a, double t) const {
  const Active A = active(a, t);
  return A.seg->p(t - A.seg->start);
}

}  // namespace kinray
