#pragma once
// The slab test of one ray against four float boxes at once (SSE, on every x86-64), conservative:
// it may keep a box the ray misses by a few ulps, never drop one the ray meets, so a traversal
// through it finds exactly the hits of the exact double triangle test (FrameBoxes).
//
// Why it cannot drop a box (after Ize, "Robust BVH Ray Traversal", JCGT 2013):
//   - The direction is scaled so that its largest component is +-1 (s becomes s * scale). An
//     axis whose inverse would exceed 2^60 (the ray is parallel to it, or nearly) is ignored: its
//     inverse is NaN, and max/min below keep their accumulator when the axis gives NaN. Ignoring
//     a slab only widens the set of kept boxes; the largest axis is never ignored, so an empty box
//     (lo = +inf, hi = -inf) is always dropped.
//   - The origin is rounded to float twice per axis, towards the side that makes that axis's
//     entry parameter smaller (o_near) and its exit parameter larger (o_far): the origin's
//     rounding then only widens the interval.
//   - What is left is relative rounding: (plane - o) rounds once, the inverse twice (double, then
//     float), the product once, so each parameter is off by at most 3.01 * 2^-24 of itself. The
//     entry (never negative: rays start at s_min >= 0) is scaled by 1 - 2^-20 and the exit by
//     1 + 2^-20 (room for that and for the margin's own rounding), then moved by 2^-50 (flushed
//     subnormals: the products and differences that underflow are below 2^-66 in these units).
//     Each rounding keeps the sign of what it rounds, so a negative exit is an exit behind the
//     origin, which the scaling may lower without dropping a box the ray meets.
//   - +-inf stays +-inf through the margins, so a box entered only at infinity is kept when s_max
//     is infinite.
#include <xmmintrin.h>

#include <Eigen/Core>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace kinray {

/// The float next to a float f that is not NaN, towards -inf (or +inf): one step of its bits.
[[nodiscard]] inline float float_step_down(float f) {
  if (f == 0) return -0x1p-149f;
  const auto bits = std::bit_cast<uint32_t>(f);
  return std::bit_cast<float>(f > 0 ? bits - 1 : bits + 1);
}
[[nodiscard]] inline float float_step_up(float f) {
  return -float_step_down(-f);
}

/// x rounded to the nearest float, beyond the float range +-inf (a plain conversion of such a
/// double is undefined behaviour), NaN kept.
[[nodiscard]] inline float to_float(double x) {
  constexpr double kMax = 3.4028235677973366e38;  // FLT_MAX rounded up: beyond it, inf
  if (x > kMax) return INFINITY;
  if (x < -kMax) return -INFINITY;
  return static_cast<float>(x);
}
/// Rounds to a float <= x (or >= x).
[[nodiscard]] inline float float_down(double x) {
  const float f = to_float(x);
  return double(f) > x ? float_step_down(f) : f;
}
[[nodiscard]] inline float float_up(double x) {
  const float f = to_float(x);
  return double(f) < x ? float_step_up(f) : f;
}

/// A ray (origin + s direction, s_min < s < s_max) ready for wide_slab_test.
class WideRay {
 public:
  WideRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double s_min,
          double s_max) {
    m_scale = direction.cwiseAbs().maxCoeff();
    for (int a = 0; a < 3; ++a) {
      const double inv = m_scale / direction[a];  // 1 / (direction / scale), |inv| >= 1
      const bool ignored = !(std::fabs(inv) <= 0x1p60);
      const bool forward = !std::signbit(inv);
      m_inv[a] = _mm_set1_ps(ignored ? NAN : static_cast<float>(inv));
      // The planes the ray enters and leaves by: rows 0-2 hold the low sides, 3-5 the high.
      m_near_row[a] = forward ? a : a + 3;
      m_far_row[a] = forward ? a + 3 : a;
      const float up = float_up(origin[a]), down = float_down(origin[a]);
      m_origin_near[a] = _mm_set1_ps(forward ? up : down);
      m_origin_far[a] = _mm_set1_ps(forward ? down : up);
    }
    if (!(s_min >= 0)) throw std::invalid_argument("wide slab test: the ray starts at s_min < 0");
    m_s_min = _mm_set1_ps(float_down(s_min * m_scale));
    set_s_max(s_max);
  }
  /// A closest-hit traversal shrinks the interval to its nearest hit so far.
  void set_s_max(double s_max) { m_s_max = _mm_set1_ps(float_up(s_max * m_scale)); }

  /// Bit k set when the ray may meet box k; bounds[r][k] is row r (lo x, lo y, lo z, hi x, hi y,
  /// hi z) of box k. entry[k] gets the (lowered) parameter where it enters, in scaled units.
  [[nodiscard]] int test(const float (&bounds)[6][4], float (&entry)[4]) const {
    __m128 near = m_s_min, far = m_s_max;
    for (int a = 0; a < 3; ++a) {
      const __m128 t0 =
          _mm_mul_ps(_mm_sub_ps(_mm_load_ps(bounds[m_near_row[a]]), m_origin_near[a]), m_inv[a]);
      const __m128 t1 =
          _mm_mul_ps(_mm_sub_ps(_mm_load_ps(bounds[m_far_row[a]]), m_origin_far[a]), m_inv[a]);
      near = _mm_max_ps(t0, near);  // NaN t0 (an ignored axis) keeps near
      far = _mm_min_ps(t1, far);
    }
    // near >= s_min >= 0 and never NaN (max keeps its accumulator): lowering it is one product.
    near = _mm_sub_ps(_mm_mul_ps(near, _mm_set1_ps(1 - 0x1p-20f)), _mm_set1_ps(0x1p-50f));
    far = _mm_add_ps(_mm_mul_ps(far, _mm_set1_ps(1 + 0x1p-20f)), _mm_set1_ps(0x1p-50f));
    _mm_storeu_ps(entry, near);
    return _mm_movemask_ps(_mm_cmple_ps(near, far));
  }
  /// A parameter s in the scaled units of test()'s entries, rounded up.
  [[nodiscard]] float scaled_up(double s) const { return float_up(s * m_scale); }

 private:
  double m_scale = 1;
  __m128 m_inv[3], m_origin_near[3], m_origin_far[3], m_s_min, m_s_max;
  int m_near_row[3], m_far_row[3];
};

}  // namespace kinray
