#pragma once
// Keys that are piecewise polynomials of time, renewed at their segments' starts.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "kinetic/core/certificate_schedule.h"
#include "kinetic/core/polynomial.h"
#include "kinetic/sort/sort_keys.h"

namespace kinray {

/// Keys that are piecewise polynomials of time: object id follows segment k from its start on,
/// key(t) = p_k(t - start_k). Certificates use the origin max(start_a, start_b) and end at the
/// next segment start of either object (so a structure renews them there by itself).
class PolynomialKeys {
 public:
  uint32_t add(const Polynomial& p, double start = 0);
  /// A new object with exactly the motion (all segments) of `other`: equal keys.
  uint32_t add_copy(uint32_t other);
  /// From `start` on, key(t) = p(t - start); later segments are dropped. Then call
  /// replace_motion(id, now) on the structures holding id.
  void set_motion(uint32_t id, const Polynomial& p, double start);
  /// Append a segment beginning at start (> the last start). Certificates computed before do not
  /// know their new end: call replace_motion(id, now) on the structures holding id.
  void append_motion(uint32_t id, const Polynomial& p, double start);
  [[nodiscard]] size_t size() const { return m_objects.size(); }
  [[nodiscard]] OrderCertificate order_certificate(uint32_t a, uint32_t b, double t) const;
  [[nodiscard]] double value(uint32_t a, double t) const;

 private:
  struct Segment {
    double start = 0;
    Polynomial p;
  };
  struct Active {
    const Segment* seg;
    double next_start;
  };
  [[nodiscard]] Active active(uint32_t id, double t) const;
  std::vector<std::vector<Segment>> m_objects;
};

static_assert(KineticKeys<PolynomialKeys>);

}  // namespace kinray
