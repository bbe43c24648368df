#include "kinetic/core/polynomial.h"

#include <algorithm>
#include <utility>

#include "kinetic/core/binomial.h"
#include "util/check.h"

namespace kinray {

namespace {
constexpr int kN = kMaxPolynomialDegree;

using detail::kBinomial;
}  // namespace

Polynomial::Polynomial(double constant) { c[0] = constant; }

Polynomial::Polynomial(std::initializer_list<double> coefficients) {
  KINRAY_CHECK(coefficients.size() <= static_cast<size_t>(kN + 1));
  int i = 0;
  for (double x : coefficients) c[i++] = x;
  degree = std::max(0, i - 1);
}

Polynomial Polynomial::derivative() const {
  Polynomial d;
  for (int k = 1; k <= degree; ++k) d.c[k - 1] = k * c[k];
  d.degree = std::max(0, degree - 1);
  return d;
}

Polynomial Polynomial::trimmed() const {
  Polynomial p = *this;
  p.degree = effective_degree();
  return p;
}

Polynomial operator+(const Polynomial& f, const Polynomial& g) {
  Polynomial h;
  h.degree = std::max(f.degree, g.degree);
  for (int k = 0; k <= h.degree; ++k) h.c[k] = f.c[k] + g.c[k];
  return h;
}

Polynomial operator-(const Polynomial& f, const Polynomial& g) {
  Polynomial h;
  h.degree = std::max(f.degree, g.degree);
  for (int k = 0; k <= h.degree; ++k) h.c[k] = f.c[k] - g.c[k];
  return h;
}

Polynomial operator-(const Polynomial& f) {
  Polynomial h = f;
  for (int k = 0; k <= h.degree; ++k) h.c[k] = -h.c[k];
  return h;
}

namespace {

/// The product of f and g of effective degrees df and dg. Pairs (i, k-i) and (k-i, i) are summed
/// together so that f * g == g * f bit for bit.
Polynomial product(const Polynomial& f, const Polynomial& g, int df, int dg) {
  Polynomial h;
  h.degree = df + dg;
  for (int k = 0; k <= h.degree; ++k) {
    double sum = 0;
    for (int i = 0; 2 * i <= k; ++i) {
      const int j = k - i;
      double term;
      if (i == j) {
        term = (i <= df && i <= dg) ? f.c[i] * g.c[i] : 0.0;
      } else {
        const double x = (i <= df && j <= dg) ? f.c[i] * g.c[j] : 0.0;
        const double y = (j <= df && i <= dg) ? f.c[j] * g.c[i] : 0.0;
        term = x + y;
      }
      sum += term;
    }
    h.c[k] = sum;
  }
  return h;
}

/// product(f, g, DF, DG) written out for degrees known at compile time: coefficient K, its
/// terms I in the same order, the same operations (a product out of the degrees is the same 0.0).
template <int DF, int DG, int K, int I>
double product_sum(const Polynomial& f, const Polynomial& g, double sum) {
  if constexpr (2 * I > K) {
    return sum;
  } else {
    constexpr int J = K - I;
    double term;
    if constexpr (I == J) {
      term = (I <= DF && I <= DG) ? f.c[I] * g.c[I] : 0.0;
    } else {
      const double x = (I <= DF && J <= DG) ? f.c[I] * g.c[J] : 0.0;
      const double y = (J <= DF && I <= DG) ? f.c[J] * g.c[I] : 0.0;
      term = x + y;
    }
    return product_sum<DF, DG, K, I + 1>(f, g, sum + term);
  }
}

template <int DF, int DG, size_t... K>
Polynomial product_of(const Polynomial& f, const Polynomial& g, std::index_sequence<K...>) {
  Polynomial h;
  h.degree = DF + DG;
  ((h.c[K] = product_sum<DF, DG, int(K), 0>(f, g, 0.0)), ...);
  return h;
}

template <int DF, int DG>
Polynomial product_of(const Polynomial& f, const Polynomial& g) {
  return product_of<DF, DG>(f, g, std::make_index_sequence<size_t(DF + DG + 1)>());
}

}  // namespace

Polynomial operator*(const Polynomial& f, const Polynomial& g) {
  const int df = f.effective_degree(), dg = g.effective_degree();
  KINRAY_CHECK_MSG(df + dg <= kN, "polynomial product exceeds kMaxPolynomialDegree");
  // The frequent degrees written out: a boundary's depth (1 by 1) and a depth certificate's
  // N D (3 by 2, 2 by 3).
  if (df == 1 && dg == 1) return product_of<1, 1>(f, g);
  if (df == 3 && dg == 2) return product_of<3, 2>(f, g);
  if (df == 2 && dg == 3) return product_of<2, 3>(f, g);
  return product(f, g, df, dg);
}

Polynomial detail::general_product(const Polynomial& f, const Polynomial& g) {
  return product(f, g, f.effective_degree(), g.effective_degree());
}

Polynomial operator*(double k, const Polynomial& f) {
  Polynomial h = f;
  for (int i = 0; i <= h.degree; ++i) h.c[i] = k * f.c[i];
  return h;
}

bool operator==(const Polynomial& f, const Polynomial& g) {
  for (int k = 0; k <= kN; ++k)
    if (f.c[k] != g.c[k]) return false;
  return true;
}

Polynomial shifted(const Polynomial& f, double shift) {
  Polynomial g = f;
  const int n = f.degree;
  // Repeated synthetic division (Taylor shift); the first pass is Horner's rule for f(shift).
  for (int i = 0; i < n; ++i)
    for (int k = n - 1; k >= i; --k) g.c[k] += shift * g.c[k + 1];
  return g;
}

Polynomial scaled(const Polynomial& f, double k) {
  Polynomial g = f;
  double p = 1;
  for (int i = 1; i <= f.degree; ++i) {
    p *= k;
    g.c[i] *= p;
  }
  return g;
}

BernsteinPolynomial to_bernstein(const Polynomial& f, double a, double b) {
  KINRAY_CHECK(a < b);
  const int n = f.degree;
  const Polynomial g = scaled(shifted(f, a), b - a);  // g(u) = f(a + (b - a) u)
  BernsteinPolynomial r;
  r.degree = n;
  r.a = a;
  r.bnd = b;
  // b_i = sum_{j <= i} C(i, j) / C(n, j) g_j
  for (int i = 0; i <= n; ++i) {
    double s = 0;
    for (int j = 0; j <= i; ++j) s += kBinomial[i][j] / kBinomial[n][j] * g.c[j];
    r.b[i] = s;
  }
  return r;
}

Polynomial to_power(const BernsteinPolynomial& f) {
  const int n = f.degree;
  // g_j = C(n, j) sum_{i <= j} (-1)^(j-i) C(j, i) b_i, polynomial in u.
  Polynomial g;
  g.degree = n;
  for (int j = 0; j <= n; ++j) {
    double s = 0;
    for (int i = 0; i <= j; ++i) s += ((j - i) % 2 ? -1.0 : 1.0) * kBinomial[j][i] * f.b[i];
    g.c[j] = kBinomial[n][j] * s;
  }
  // u = (s - a) / w  ->  scale by 1/w, then shift by -a.
  const double w = f.bnd - f.a;
  Polynomial h;
  h.degree = n;
  double p = 1;
  for (int j = 0; j <= n; ++j) {
    h.c[j] = g.c[j] / p;
    p *= w;
  }
  return shifted(h, -f.a);
}

double evaluate(const BernsteinPolynomial& f, double s) {
  const double u = (s - f.a) / (f.bnd - f.a);
  std::array<double, kN + 1> t = f.b;
  for (int r = 1; r <= f.degree; ++r)
    for (int i = 0; i <= f.degree - r; ++i) t[i] = (1 - u) * t[i] + u * t[i + 1];
  return t[0];
}

std::pair<BernsteinPolynomial, BernsteinPolynomial> subdivide(const BernsteinPolynomial& f,
                                                              double s) {
  KINRAY_CHECK(f.a < s && s < f.bnd);
  const int n = f.degree;
  const double u = (s - f.a) / (f.bnd - f.a);
  BernsteinPolynomial left, right;
  left.degree = right.degree = n;
  left.a = f.a;
  left.bnd = s;
  right.a = s;
  right.bnd = f.bnd;
  std::array<double, kN + 1> t = f.b;
  left.b[0] = t[0];
  right.b[n] = t[n];
  for (int r = 1; r <= n; ++r) {
    for (int i = 0; i <= n - r; ++i) t[i] = (1 - u) * t[i] + u * t[i + 1];
    left.b[r] = t[0];
    right.b[n - r] = t[n - r];
  }
  return {left, right};
}

}  // namespace kinray
