#pragma once
// Certificates of the kinetic core and when to look at them again: a certificate "a before b" is
// a polynomial f(t - origin) > 0 valid until `end`; schedule_certificate turns its first failure
// (root_finding.h, exact_certificate.h) into the absolute event time that the owner pushes, such
// that the handler, evaluating at that double time, sees the change. The sorts, the grid's pixel
// orders and their audits share it.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>

#include "kinetic/core/exact_certificate.h"
#include "kinetic/core/polynomial.h"

namespace kinray {

/// "a sorts before b" holds while f(t - origin) > 0, valid for t in [origin, end]
/// (end = when either motion changes next).
struct OrderCertificate {
  Polynomial f;
  double origin = 0;
  double end = std::numeric_limits<double>::infinity();
  /// When set, the exact polynomial that f rounds, too close to call in double near its roots:
  /// signs and failure times are then decided on it (kinetic/core/exact_certificate.h).
  std::shared_ptr<const ExactPolynomial> exact;
  /// With `exact`: how long the rounded envelopes were seen to decide the sign, so that the exact
  /// failure search can wait (schedule_certificate's defer_exact).
  EnvelopeVouch vouched;
  /// A key value that one key of the pair stays below and the other above through the
  /// certificate's window, when the keys proved the pair apart with it (f's sign says which is
  /// which); NaN otherwise. A certificate of one of the two with the other's replacement then
  /// needs only the replacement's side of it (order_certificate_beside, kinetic_sort.h). A float:
  /// the sorted list keeps one per adjacent pair.
  float separator = std::numeric_limits<float>::quiet_NaN();

  /// The certificate of the swapped pair: -f (exactly, as the keys contract requires). The
  /// separator stays: the sides swap with f's sign.
  void negate() {
    // In place, coefficient by coefficient as operator- negates (a copy of the whole array cost
    // a pixel order's hand-over more than the negation).
    for (int k = 0; k <= f.degree; ++k) f.c[size_t(k)] = -f.c[size_t(k)];
    if (exact) exact = exact_negated(*exact);
    vouched.orientation = -vouched.orientation;
  }
};

namespace detail {

/// Sign of c's polynomial just after local time s (exact when c carries its exact polynomial).
[[nodiscard]] int certificate_sign_after(const OrderCertificate& c, double s);

/// Sign of "a before b" just after `now` for certificate c of (a, b): +1, -1, or by the id rule
/// when f is the zero polynomial.
[[nodiscard]] int order_sign(const OrderCertificate& c, double now, uint32_t a, uint32_t b);

/// When to look at certificate c of (a, b) again, computed at `now`.
struct Schedule {
  double time = std::numeric_limits<double>::infinity();  ///< +inf: never
  bool failure = false;     ///< true: c fails at `time`; false: renewal at c.end (or never)
  bool degenerate = false;  ///< a near-tie was given up (see schedule_degenerate)
  double broken_until = -std::numeric_limits<double>::infinity();  ///< degenerate: c < 0 until
  /// `time` is where the filter's vouch for c's exact polynomial ends (it holds at every double
  /// before): the exact failure search was put off until then.
  bool recheck = false;
};
/// The absolute event time of certificate c of (a, b) (already holding just after now, or
/// broken: then time = now). The time t returned for a failure satisfies
/// sign_after(f, t - origin) < 0 with the subtraction in double, as the structure will compute
/// it when the event is handled, so processing the swap gives a successor that holds.
///
/// With `defer_exact`, a certificate decided on its exact polynomial whose filter vouched for it
/// past now (`vouched`) is scheduled for a recheck where that vouch ends (`recheck`), never later
/// than its failure: most such pairs stop being neighbours before then (a triangle leaves the
/// pixel), and the exact search, ten times the rest of the certificate, is never run. The
/// structure recomputes the certificate at the recheck as at any event, finds it holding, and
/// schedules it again from there, then exactly (the new vouch ends at once).
[[nodiscard]] Schedule schedule_certificate(const OrderCertificate& c, double now, uint32_t a,
                                            uint32_t b, bool defer_exact = false);

/// Same-instant guard: counts events per instant; beyond a budget, a certificate created broken
/// at now is treated as a numerical near-tie and scheduled after its next - to + change.
[[nodiscard]] Schedule schedule_degenerate(const OrderCertificate& c, double now, uint32_t a,
                                           uint32_t b);

}  // namespace detail

}  // namespace kinray
