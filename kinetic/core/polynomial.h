#pragma once
// Polynomials of small degree in the power and Bernstein bases: the certificates of kinray.

#include <array>
#include <cstddef>
#include <initializer_list>
#include <utility>

namespace kinray {

inline constexpr int kMaxPolynomialDegree = 8;

/// A polynomial of degree <= 8 in the power basis: c[0] + c[1] s + ... (s is a local time
/// variable chosen by the caller).
struct Polynomial {
  std::array<double, kMaxPolynomialDegree + 1> c{};  ///< unused high coefficients are 0
  int degree = 0;  ///< index of the highest stored coefficient (may be 0 even if c[0] == 0)

  Polynomial() = default;
  explicit Polynomial(double constant);
  /// Coefficients from low to high order; at most kMaxPolynomialDegree + 1 of them.
  Polynomial(std::initializer_list<double> coefficients);

  /// Horner's rule, highest stored coefficient first. Inline: every event evaluates a few.
  [[nodiscard]] double operator()(double s) const {
    double acc = c[std::size_t(degree)];
    for (int k = degree - 1; k >= 0; --k) acc = acc * s + c[std::size_t(k)];
    return acc;
  }
  [[nodiscard]] Polynomial derivative() const;
  [[nodiscard]] bool is_zero() const {
    for (int k = 0; k <= degree; ++k)
      if (c[std::size_t(k)] != 0) return false;
    return true;
  }
  /// Index of the highest non-zero coefficient (0 for the zero polynomial).
  [[nodiscard]] int effective_degree() const {
    int d = degree;
    while (d > 0 && c[std::size_t(d)] == 0) --d;
    return d;
  }
  /// The same polynomial with `degree` lowered to effective_degree().
  [[nodiscard]] Polynomial trimmed() const;
};

Polynomial operator+(const Polynomial& f, const Polynomial& g);
/// Coefficient-wise f - g; exactly the negation of g - f (IEEE subtraction is antisymmetric).
Polynomial operator-(const Polynomial& f, const Polynomial& g);
Polynomial operator-(const Polynomial& f);
/// Product; KINRAY_CHECK on degree overflow (of the effective degrees). Exactly commutative:
/// every coefficient sums the products pairwise in a symmetric order.
Polynomial operator*(const Polynomial& f, const Polynomial& g);
Polynomial operator*(double k, const Polynomial& f);
bool operator==(const Polynomial& f, const Polynomial& g);  ///< same coefficients (degree aside)

namespace detail {
/// f * g by the general loop of operator* (which writes the frequent degrees out, to the same
/// doubles): for tests that check the written-out products against it.
Polynomial general_product(const Polynomial& f, const Polynomial& g);
}  // namespace detail

/// f(s + shift) as a polynomial in s (re-centre the local time origin); Taylor shift.
Polynomial shifted(const Polynomial& f, double shift);
/// f(k s) as a polynomial in s.
Polynomial scaled(const Polynomial& f, double k);

/// A polynomial in the Bernstein basis of degree `degree` on [a, bnd]:
/// f(s) = sum_i b[i] C(n,i) u^i (1-u)^(n-i), u = (s - a) / (bnd - a).
struct BernsteinPolynomial {
  std::array<double, kMaxPolynomialDegree + 1> b{};
  int degree = 0;
  double a = 0, bnd = 1;
};

/// Bernstein form of f on [a, b] (a < b, both finite), degree f.degree.
BernsteinPolynomial to_bernstein(const Polynomial& f, double a, double b);
/// Back to the power basis in s (the same variable as the one to_bernstein was given).
Polynomial to_power(const BernsteinPolynomial& f);
/// de Casteljau evaluation at s (any s; extrapolates outside [a, bnd]).
double evaluate(const BernsteinPolynomial& f, double s);
/// Split at s (a < s < bnd) into the Bernstein forms on [a, s] and [s, bnd] (de Casteljau).
std::pair<BernsteinPolynomial, BernsteinPolynomial> subdivide(const BernsteinPolynomial& f,
                                                              double s);

}  // namespace kinray
