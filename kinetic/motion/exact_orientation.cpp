#include "kinetic/motion/exact_orientation.h"

#include <gmpxx.h>

#include <array>

#include "kinetic/motion/triangle_motion.h"

namespace kinray {

namespace {

/// A polynomial in s with rational coefficients, just big enough for a cubic.
using Exact = std::array<mpq_class, 4>;

/// Component k of a vertex motion, a + b s, as an exact linear polynomial.
Exact component(const PointMotion& p, int k) {
  Exact e;
  e[0] = p.a[k];
  e[1] = p.b[k];
  return e;
}

Exact times(const Exact& f, const Exact& g) {
  Exact h;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; i + j < 4; ++j)
      if (f[i] != 0 && g[j] != 0) h[i + j] += f[i] * g[j];
  return h;
}

}  // namespace

Polynomial exact_orientation(const TriangleMotion& m) {
  // det = sum over the permutations (i, j, k) of {0, 1, 2} of sign * v0_i v1_j v2_k.
  static constexpr std::array<std::array<int, 4>, 6> kTerms = {
      {{0, 1, 2, 1}, {1, 2, 0, 1}, {2, 0, 1, 1}, {0, 2, 1, -1}, {1, 0, 2, -1}, {2, 1, 0, -1}}};
  Exact sum;
  for (const auto& [i, j, k, sign] : kTerms) {
    const Exact term = times(times(component(m.v[0], i), component(m.v[1], j)), component(m.v[2], k));
    for (size_t c = 0; c < 4; ++c) {
      if (sign > 0)
        sum[c] += term[c];
      else
        sum[c] -= term[c];
    }
  }
  Polynomial o;
  o.degree = 3;
  for (size_t c = 0; c < 4; ++c) o.c[c] = sum[c].get_d();  // mpq_get_d truncates toward zero
  return o;
}

}  // namespace kinray
