#pragma once
// A conservative rejection ahead of the exact ray-triangle test (ray_triangle.h): from the
// frame's float vertex points (FrameBoxes), it answers "certainly missed" only when the exact
// test on the exact double positions reports a miss too, and otherwise "test it". Nearly every
// triangle a shadow ray's traversal reaches is missed (98% on wavy-sphere), most of them by far,
// and the exact test's cost is mostly reading and blending the three positions.
//
// Why a rejection is sound: each point differs from the exact position by at most eta per
// coordinate, eta = 2^-22 L + slack + 1e-30 with L >= every |coordinate| (the meshes' scale):
// a float rounded to nearest is within 2^-24 L (2^-150 below the normal floats), and `slack`
// bounds how far the points' double source may be from the exact test's positions (the frame's
// pad: a + b (t - o) against the key blend). The factor 4 of 2^-22 covers the double rounding of
// the few operations here and in the exact test. Moeller-Trumbore's numerators are triple
// products,
//   det = e1 . (d x e2), u = o . (d x e2), v = d . (o x e1),   o = origin - p0, e_k = p_k - p0,
// and u and v keep their value when o moves along d: o is replaced by its part across the ray,
// o - lambda d for the computed lambda (whose rounding, below 2^-48 (|origin| + L), is added to
// o's error), about the triangle's size for the triangles a ray passes near, where |o| may be far
// larger. A triple product a . (d x b) whose factors are off by at most alpha and beta, with
// |a| <= A and |b| <= B (bounds of the exact factors), is off by at most
// 6 |d| (alpha B + A beta + alpha beta), |d| the direction's largest |component|; e_k is off by
// 2 eta. So when |det| exceeds its bound, the exact det has the same sign sigma, and
// sigma u < -bound_u means u < 0 there (u > 1, v < 0 and u + v > 1 alike, with the bounds of each
// numerator added; the margins are some 2^-23 of |det| at least, far above the exact test's
// rounding of u and v): a miss. NaN and infinite values (points beyond the float range) compare
// false and reject nothing.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace kinray {

class RayTriangleFilter {
 public:
  /// scale: at least every |coordinate| of the triangles tested; slack: see above.
  RayTriangleFilter(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double scale,
                    double slack)
      : m_origin{origin.x(), origin.y(), origin.z()},
        m_direction{direction.x(), direction.y(), direction.z()},
        m_inverse_norm2(1 / direction.squaredNorm()) {
    const double eta = 0x1p-22 * scale + slack + 1e-30;
    m_edge_error = 2 * eta;
    m_across_error = eta + 0x1p-48 * (origin.cwiseAbs().maxCoeff() + scale);
    m_scale = 6 * direction.cwiseAbs().maxCoeff();
  }

  /// True when the ray certainly misses the triangle whose vertex points (x, y, z, unused) are
  /// given: ray_triangle on the exact positions returns std::nullopt.
  [[nodiscard]] bool misses(const float* q0, const float* q1, const float* q2) const {
    const double* d = m_direction;
    double e1[3], e2[3], o[3];
    for (int a = 0; a < 3; ++a) {
      const double p0 = q0[a];
      e1[a] = double(q1[a]) - p0;
      e2[a] = double(q2[a]) - p0;
      o[a] = m_origin[a] - p0;
    }
    const double lambda = (o[0] * d[0] + o[1] * d[1] + o[2] * d[2]) * m_inverse_norm2;
    double across[3];
    for (int a = 0; a < 3; ++a) across[a] = o[a] - lambda * d[a];
    const double p[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2],
                         d[0] * e2[1] - d[1] * e2[0]};
    const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    const double e1_size = largest(e1) + m_edge_error, e2_size = largest(e2) + m_edge_error;
    const double bound_det = m_scale * m_edge_error * (e1_size + e2_size + m_edge_error);
    if (!(std::fabs(det) > bound_det)) return false;  // NaN, or a sign the points cannot give
    const double sigma = det > 0 ? 1 : -1;
    const double across_size = largest(across) + m_across_error;
    const double common = across_size * m_edge_error + m_across_error * m_edge_error;
    const double bound_u = m_scale * (m_across_error * e2_size + common);
    const double u = sigma * (across[0] * p[0] + across[1] * p[1] + across[2] * p[2]);
    const double n = sigma * det;
    if (u < -bound_u || u - n > bound_u + bound_det) return true;
    const double bound_v = m_scale * (m_across_error * e1_size + common);
    const double q[3] = {across[1] * e1[2] - across[2] * e1[1],
                         across[2] * e1[0] - across[0] * e1[2],
                         across[0] * e1[1] - across[1] * e1[0]};
    const double v = sigma * (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]);
    return v < -bound_v || u + v - n > bound_u + bound_v + bound_det;
  }

 private:
  [[nodiscard]] static double largest(const double (&x)[3]) {
    return std::max(std::max(std::fabs(x[0]), std::fabs(x[1])), std::fabs(x[2]));
  }

  double m_origin[3], m_direction[3];
  double m_inverse_norm2;  ///< inf for a zero direction: nothing rejected (det is 0)
  double m_edge_error = 0, m_across_error = 0, m_scale = 0;
};

}  // namespace kinray
