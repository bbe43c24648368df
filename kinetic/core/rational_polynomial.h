#pragma once
// Polynomials with exact rational coefficients (GMP) and their real roots, isolated by exact
// Descartes/Bernstein bisection: the arithmetic that decides a continuous collision exactly when
// floating point cannot.
#include <gmpxx.h>

#include <span>
#include <vector>

namespace kinray {

/// A polynomial in t with rational coefficients c[0] + c[1] t + ...; no trailing zero
/// coefficients, so the zero polynomial has none.
struct RationalPolynomial {
  std::vector<mpq_class> c;

  RationalPolynomial() = default;
  explicit RationalPolynomial(std::vector<mpq_class> coefficients);
  /// a + b t
  static RationalPolynomial linear(const mpq_class& a, const mpq_class& b);

  [[nodiscard]] int degree() const { return static_cast<int>(c.size()) - 1; }  ///< -1 for zero
  [[nodiscard]] bool is_zero() const { return c.empty(); }
  [[nodiscard]] mpq_class operator()(const mpq_class& t) const;  ///< Horner, exact
  [[nodiscard]] RationalPolynomial derivative() const;
};

RationalPolynomial operator+(const RationalPolynomial& f, const RationalPolynomial& g);
RationalPolynomial operator-(const RationalPolynomial& f, const RationalPolynomial& g);
RationalPolynomial operator*(const RationalPolynomial& f, const RationalPolynomial& g);

/// Greatest common divisor, monic (the zero polynomial when both are zero).
RationalPolynomial gcd(RationalPolynomial f, RationalPolynomial g);
/// f / gcd(f, f'): the same roots, each simple.
RationalPolynomial squarefree_part(const RationalPolynomial& f);
/// Sign (-1, 0, 1) of a rational.
int sign(const mpq_class& x);

/// Gives GMP back its own allocation functions (malloc, realloc, free). A library loaded with
/// the program may have replaced them: gnutls (under OpenCV's video I/O, through ffmpeg) zeroes
/// every block before freeing it and reallocates by copying, to wipe its keys, which made the
/// exact decisions' millions of small numbers several percent slower. Its blocks come from
/// malloc, so the defaults free them too. Call once at the start of a program.
void use_default_gmp_allocation();

/// Bernstein coefficients of f on [a, b] (a < b), degree f.degree(): f lies in their convex
/// hull on [a, b], and the number of their sign changes bounds the roots in (a, b) (Descartes).
std::vector<mpq_class> bernstein_coefficients(const RationalPolynomial& f, const mpq_class& a,
                                              const mpq_class& b);
/// The signs (-1, 0, 1) of bernstein_coefficients(f, a, b), from positive multiples of them
/// computed in integers: the exact isolation needs only these, and they cost no gcds.
std::vector<int> bernstein_signs(const RationalPolynomial& f, const mpq_class& a,
                                 const mpq_class& b);

/// A real algebraic number: the only root of `poly` in [lo, hi], a simple one (poly is
/// square-free, or has no multiple root in [lo, hi]). Either lo == hi (a rational root) or
/// poly(lo) and poly(hi) are non-zero of opposite signs.
struct IsolatedRoot {
  RationalPolynomial poly;
  mpq_class lo, hi;

  [[nodiscard]] bool is_rational() const { return lo == hi; }
  /// Halves [lo, hi], keeping the root inside (or lands on it exactly).
  void refine();
  /// Refines until hi - lo <= width.
  void refine_to(const mpq_class& width);
};

/// Every real root of f in the closed interval [lo, hi], in increasing order, each once
/// (f non-zero; f need not be square-free).
std::vector<IsolatedRoot> isolate_roots(const RationalPolynomial& f, const mpq_class& lo,
                                        const mpq_class& hi);

/// The exact sign of g at the root: zero when g vanishes there (decided by gcd, not by a
/// tolerance), otherwise by refining the root until g's Bernstein coefficients on its interval
/// agree in sign. Refines `root` in place.
int sign_at(const RationalPolynomial& g, IsolatedRoot& root);

}  // namespace kinray
