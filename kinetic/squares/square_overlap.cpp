#include "kinetic/squares/square_overlap.h"

#include <array>
#include <cmath>
#include <vector>

namespace kinray {

namespace {

constexpr double kTolerance = 1e-9;

/// The three half-planes a x + b y + c >= 0 of R (the edge functions times sign O), each with
/// its tolerance; false when O is too close to zero to tell R's sides.
struct HalfPlanes {
  std::array<Eigen::Vector3d, 3> h;
  std::array<double, 3> tolerance{};
  bool decided = false;
  int orientation = 0;
};

HalfPlanes half_planes(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                       const Eigen::Vector3d& p2) {
  HalfPlanes r;
  const double o = p0.dot(p1.cross(p2));
  const double scale = p0.norm() * p1.norm() * p2.norm();
  r.orientation = o > 0 ? 1 : (o < 0 ? -1 : 0);
  r.decided = std::fabs(o) > kTolerance * scale;
  const std::array<const Eigen::Vector3d*, 3> v = {&p0, &p1, &p2};
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector3d n = v[size_t(e)]->cross(*v[size_t((e + 1) % 3)]);
    r.h[size_t(e)] = r.orientation * n;
    // The image coordinates are O(1) (|x| <= aspect, |y| <= 1), so this bounds the error of the
    // edge function's value and the distance a tie hides in, relative to the edge's scale.
    r.tolerance[size_t(e)] = 4 * kTolerance * n.cwiseAbs().sum();
  }
  return r;
}

/// Sutherland-Hodgman: the convex polygon `poly` clipped by a x + b y + c >= offset.
std::vector<Eigen::Vector2d> clip(const std::vector<Eigen::Vector2d>& poly,
                                  const Eigen::Vector3d& h, double offset) {
  std::vector<Eigen::Vector2d> out;
  const size_t n = poly.size();
  for (size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d& a = poly[k];
    const Eigen::Vector2d& b = poly[(k + 1) % n];
    const double fa = h.x() * a.x() + h.y() * a.y() + h.z() - offset;
    const double fb = h.x() * b.x() + h.y() * b.y() + h.z() - offset;
    if (fa >= 0) out.push_back(a);
    if ((fa >= 0) != (fb >= 0)) out.push_back(a + (fa / (fa - fb)) * (b - a));
  }
  return out;
}

bool clipped_nonempty(const HalfPlanes& r, const ImageSquare& s, double sign) {
  std::vector<Eigen::Vector2d> poly = {{s.x0, s.y0}, {s.x1, s.y0}, {s.x1, s.y1}, {s.x0, s.y1}};
  for (int e = 0; e < 3 && !poly.empty(); ++e)
    poly = clip(poly, r.h[size_t(e)], sign * r.tolerance[size_t(e)]);
  return !poly.empty();
}

}  // namespace

Overlap square_overlap(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                       const Eigen::Vector3d& p2, const ImageSquare& square) {
  const HalfPlanes r = half_planes(p0, p1, p2);
  if (!r.decided) {
    // O near zero: R is a sliver around a line (or empty), whatever its sides: only a square
    // clear of all three loosened half-planes of both orientations is a clear "no".
    HalfPlanes other = r;
    for (auto& h : other.h) h = -h;
    return clipped_nonempty(r, square, -1) || clipped_nonempty(other, square, -1) ? Overlap::kTie
                                                                                  : Overlap::kNo;
  }
  if (clipped_nonempty(r, square, 1)) return Overlap::kYes;
  return clipped_nonempty(r, square, -1) ? Overlap::kTie : Overlap::kNo;
}

Overlap ray_pierces(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                    double x, double y) {
  const HalfPlanes r = half_planes(p0, p1, p2);
  if (!r.decided) return Overlap::kTie;
  bool clear = true;
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector3d& h = r.h[size_t(e)];
    const double v = h.x() * x + h.y() * y + h.z();
    if (v < -r.tolerance[size_t(e)]) return Overlap::kNo;
    if (v <= r.tolerance[size_t(e)]) clear = false;
  }
  return clear ? Overlap::kYes : Overlap::kTie;
}

}  // namespace kinray
