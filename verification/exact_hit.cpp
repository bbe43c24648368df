#include "verification/exact_hit.h"

#include <algorithm>
#include <cmath>

namespace kinray {

// Why these tolerances (TieTolerance):
//
// Edge, 1e-5. The edge function E_pq(d) = (p x q) . d decides which side of edge pq the ray
// passes. Embree and GL evaluate it in float from float-rounded vertices: rounding p or q moves
// (p x q) . d by about 2^-24 |p| |q| |d| per operation, and their edge tests take a handful of
// operations, so their error stays below ~1e-6 |p| |q| |d|. Measuring the ray's distance from the
// edge as |E_pq(d)| / (|p| |q| |d|) puts that error on one scale for every triangle size and
// distance; 1e-5 (about 170 float ulps) is ten times the worst float error, and still far below a
// pixel for every triangle more than a few pixels across (for a triangle subtending an angle a,
// the zone is about 1e-5 / a of its width).
//
// Depth, 1e-6. Rounding the vertices to float moves a triangle's plane by ~2^-24 |p|, which moves
// the depth of its hit by ~2^-24 z / cos(theta) (theta between the ray and the normal); the float
// depth arithmetic adds a few ulps more. 1e-6 z / cos(theta) is 16 ulps. 1 / cos is capped at 1000:
// at grazing incidence nearly every depth would otherwise be a tie.
namespace {

constexpr double kMaxGrazing = 1e3;

double margin_of(const Vec3& p, const Vec3& q, const Vec3& d, double sign) {
  const double scale = p.norm() * q.norm() * d.norm();
  return scale > 0 ? sign * p.cross(q).dot(d) / scale : 0.0;
}

}  // namespace

ExactHit exact_hit(const std::array<Vec3, 3>& v, const Vec3& d, double edge_tolerance) {
  ExactHit hit;
  // docs/design.md, "The sign rule": the ray pierces (v0, v1, v2) iff the three edge functions have
  // the sign of O = det(v0, v1, v2); the depth is O / (E01 + E12 + E20).
  const double o = v[0].dot(v[1].cross(v[2]));
  if (o == 0 || !std::isfinite(o)) return hit;  // the eye is in its plane: no ray pierces it
  const double sign = o > 0 ? 1.0 : -1.0;
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = v[size_t(k)];
    const Vec3& q = v[size_t((k + 1) % 3)];
    hit.margin[size_t(k)] = margin_of(p, q, d, sign);
    sum += p.cross(q).dot(d);
    if (std::abs(hit.margin[size_t(k)]) <= edge_tolerance) hit.near_edges |= 1u << k;
  }
  hit.z = o / sum;
  hit.valid = std::isfinite(hit.z) && hit.z > 0 &&
              std::all_of(hit.margin.begin(), hit.margin.end(),
                          [&](double m) { return m >= -edge_tolerance; });
  const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
  const double scale = n.norm() * d.norm();
  hit.cos = scale > 0 ? std::abs(n.dot(d)) / scale : 0.0;
  return hit;
}

bool same_depth(const ExactHit& a, const ExactHit& b, const TieTolerance& tolerance) {
  const double grazing = 1.0 / std::max(std::min(a.cos, b.cos), 1.0 / kMaxGrazing);
  return std::abs(a.z - b.z) <= tolerance.depth * std::max(a.z, b.z) * grazing;
}

}  // namespace kinray
