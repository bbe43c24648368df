#pragma once
// Exact certificates: when a certificate polynomial is the difference of two products of
// polynomials with double coefficients (the per-pixel depth order's N_B D_A - N_A D_B), forming
// it in double loses every significant digit where the products nearly cancel, as they do over a
// cluster of roots. There the failure time found on the rounded coefficients can be off by far
// more than an ulp (BART robots, t = 1.4997: 7e-8 s early, depths out of order by 1e-7). An
// envelope test on the rounded polynomial, widened by a bound on the rounding, tells when the
// double form decides the failure time; when it does not, the certificate carries its exact
// form, p1 q1 - p2 q2 from the double coefficients, and every sign and failure time is decided on
// it: signs by a double-double evaluation with an error bound, GMP rationals when that cannot
// tell; failure times by bisection between the envelopes' failures where the exact polynomial is
// provably monotone, by exact root isolation (GMP) otherwise.
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>

#include "kinetic/core/polynomial.h"

namespace kinray {

/// sign (p1 q1 - p2 q2) with exact value semantics: the products and the difference are those
/// of the real polynomials whose coefficients are the given doubles.
class ExactPolynomial {
 public:
  ExactPolynomial(const Polynomial& first, const Polynomial& first_factor,
                  const Polynomial& second, const Polynomial& second_factor, int sign_of_difference)
      : p1(first), q1(first_factor), p2(second), q2(second_factor), sign(sign_of_difference) {}

  Polynomial p1, q1, p2, q2;
  int sign = 1;

  struct Envelopes {
    /// sign (p1 q1 - p2 q2) with every coefficient rounded once from its exact value
    /// (compensated sums of exact products), and a bound on its distance to the exact polynomial
    /// with room for Horner's rounding: the envelopes of the failure-time search.
    Polynomial close, close_error;
    /// close -/+ close_error, rounded: F lies strictly between their Horner values for s >= 0,
    /// so that a sign of either that clears zero the right way is F's sign (exact_sign_after's
    /// first filter).
    Polynomial lower, upper;
  };
  /// Computed on first use and kept: most exact certificates are scheduled for a recheck and
  /// dropped before it (their pair parts), and never ask. Not to be called from two threads at
  /// once on one object (a structure's certificates belong to the thread that runs it).
  [[nodiscard]] const Envelopes& envelopes() const;

  /// -F, its envelopes negated if computed (the same bits as computing them: IEEE negation and
  /// rounding are symmetric).
  [[nodiscard]] ExactPolynomial negated() const;

 private:
  mutable std::optional<Envelopes> m_envelopes;
};

/// The exact form of sign (p1 q1 - p2 q2).
[[nodiscard]] std::shared_ptr<const ExactPolynomial> exact_product_difference(const Polynomial& p1,
                                                                              const Polynomial& q1,
                                                                              const Polynomial& p2,
                                                                              const Polynomial& q2,
                                                                              int sign);
/// -f, exactly.
[[nodiscard]] std::shared_ptr<const ExactPolynomial> exact_negated(const ExactPolynomial& f);

/// The exact sign (-1, 0, +1) of f just after s: the first non-vanishing derivative at s.
[[nodiscard]] int exact_sign_after(const ExactPolynomial& f, double s);
/// first_failure's contract on the exact polynomial: the first double r in (s_now, s_end]
/// (s_end may be +inf, s_now >= 0) with exact_sign_after(f, r) < 0; s_now when already broken
/// just after s_now; nullopt for the zero polynomial or when no double of (s_now, s_end] sees
/// f < 0.
[[nodiscard]] std::optional<double> exact_first_failure(const ExactPolynomial& f, double s_now,
                                                        double s_end);

/// A bound on |exact - computed| of every coefficient of p1 * q1 - p2 * q2 formed in double
/// (Polynomial's operators), with room for Horner's rounding when the result is evaluated.
/// Symmetric: swapping (p1, q1) with (p2, q2) gives the same bits.
[[nodiscard]] Polynomial product_difference_error(const Polynomial& p1, const Polynomial& q1,
                                                  const Polynomial& p2, const Polynomial& q2);

/// What the rounded envelopes of an undecided certificate still prove: the exact polynomial has
/// the sign `orientation` (+1, or -1 for its negation; 0: nothing proved) at every double of
/// (from, until), local time, so its sign just after any s of [from, until) too.
struct EnvelopeVouch {
  int orientation = 0;
  double from = std::numeric_limits<double>::infinity();
  double until = -std::numeric_limits<double>::infinity();
  [[nodiscard]] bool covers(double s) const { return orientation != 0 && s >= from && s < until; }
};

/// Does the rounded certificate f decide its failure in (s_now, s_end] (s_now >= 0), and that of
/// -f, whatever the exact polynomial within `error` (coefficient-wise) of it? One way, true when
/// f - error holds throughout, or f - error and f + error fail at the same double: the exact
/// polynomial, lying between them for s >= 0, then fails there too. Both ways, since a swap
/// schedules the negation without recomputing it. When it does not decide, `vouch` (if given)
/// receives how long the envelope of the way that holds now was seen to hold, found on the way.
[[nodiscard]] bool decided_despite(const Polynomial& f, const Polynomial& error, double s_now,
                                   double s_end, EnvelopeVouch* vouch = nullptr);

}  // namespace kinray
