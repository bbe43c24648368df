#include "kinetic/sort/polynomial_keys.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinetic/core/certificate_time.h"
#include "util/check.h"

namespace kinray {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

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
