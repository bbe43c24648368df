#pragma once
// Binomial coefficients C(n, k) for n <= kMaxPolynomialDegree, exact in double: the power <->
// Bernstein conversions and de Casteljau subdivision of polynomial.cpp and root_finding.cpp.
#include <array>

#include "kinetic/core/polynomial.h"

namespace kinray::detail {

constexpr std::array<std::array<double, kMaxPolynomialDegree + 1>, kMaxPolynomialDegree + 1> make_binomials() {
  std::array<std::array<double, kMaxPolynomialDegree + 1>, kMaxPolynomialDegree + 1> t{};
  for (int n = 0; n <= kMaxPolynomialDegree; ++n) {
    t[n][0] = 1;
    for (int k = 1; k <= n; ++k) t[n][k] = t[n - 1][k - 1] + (k <= n - 1 ? t[n - 1][k] : 0);
  }
  return t;
}
inline constexpr auto kBinomial = make_binomials();

}  // namespace kinray::detail
