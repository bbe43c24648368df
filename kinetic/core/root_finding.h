#pragma once
// Certified failure times of certificates f > 0: Bernstein fast path, de Casteljau isolation,
// Illinois / bisection refinement. See docs/kinetic_core.md, "Kinetic core".

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "kinetic/core/polynomial.h"

namespace kinray {

/// sign_after(f, s) where Horner's value f(s) is exactly 0: the sign of the first non-vanishing
/// derivative at s (0 only for the zero polynomial).
[[nodiscard]] int sign_after_root(const Polynomial& f, double s);

/// Sign (-1, 0, +1) of f just after s: the sign of the first non-vanishing derivative at s
/// (0 only for the zero polynomial). The value f(s) is Horner's, exactly as f(s). Inline: the
/// grid takes a few per event, almost always decided by the value itself.
[[nodiscard]] inline int sign_after(const Polynomial& f, double s) {
  const double v = f(s);
  return v > 0 ? 1 : (v < 0 ? -1 : sign_after_root(f, s));
}

/// The certificate f > 0 fails at the first s in (s_now, s_end] where f changes sign from + to -.
/// - If sign_after(f, s_now) < 0 the certificate is already broken: returns s_now.
/// - The zero polynomial, or no + to - change in (s_now, s_end]: std::nullopt. A root of even
///   multiplicity (a touch) is not a failure; a simple root at s_end is one.
/// - s_end may be +infinity (a root bound makes the search finite).
/// The result r > s_now satisfies sign_after(f, r) < 0 as evaluated in double, so a certificate
/// -f rebuilt at r holds just after r (no re-firing at the same instant).
[[nodiscard]] std::optional<double> first_failure(const Polynomial& f, double s_now, double s_end);
/// first_failure, the same answer, and `noise` set when the search passed over a stretch of
/// (s_now, answer] where f is within its rounding of zero (a leaf of the isolation at the noise
/// level, or a certain sign that Horner's values did not confirm) and left unsettled: there
/// Horner's values may be negative at doubles before the answer, or without an answer at all
/// (an envelope a few ulps below a near double root). Callers that take "no earlier failure"
/// as a proof about another polynomial (exact_first_failure's envelopes) check it.
[[nodiscard]] std::optional<double> first_failure(const Polynomial& f, double s_now, double s_end,
                                                  bool& noise);

/// The linear certificate c0 + c1 s > 0 holds just after s_now and at s_end (as Horner's rule
/// evaluates it, which is monotone in s), so nowhere in between does it fail: first_failure's
/// quick "no failure" for degree 1, also taken inline by callers that schedule many such
/// certificates (every band watches every vertex's row sides at every key).
[[nodiscard]] inline bool linear_holds_through(double c0, double c1, double s_now, double s_end) {
  const double v = c0 + c1 * s_now;
  return (v > 0 || (v == 0 && c1 > 0)) && (c1 > 0 || (std::isfinite(s_end) && c0 + c1 * s_end > 0));
}

/// All sign changes (either direction) in (s0, s1], ascending; for tests and audits.
/// Each reported point r is where the evaluated sign_after(f, r) takes the new sign.
std::vector<double> sign_changes(const Polynomial& f, double s0, double s1);

/// Counters of the fast path and subdivision work (thread-local, resettable), for --stats.
struct RootStats {
  uint64_t calls = 0;              ///< first_failure calls
  uint64_t fast_path_no_root = 0;  ///< decided "no failure" from one Bernstein conversion
  uint64_t subdivisions = 0;       ///< de Casteljau / reconversion steps in the slow path
  uint64_t refinements = 0;        ///< Illinois / bisection iterations
};
RootStats& root_stats();

}  // namespace kinray
