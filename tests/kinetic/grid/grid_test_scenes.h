#pragma once
// Small camera-space scenes for the kinetic grid tests, and a brute-force reference: per pixel,
// every present triangle tested by the sign rule from the positions at t (no polynomials, no
// events), the nearest hit wins. A difference between the grid and the reference is a tie only
// when both hits are at the same depth or the ray grazes an edge, within 1e-9 relative.
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>
#include <vector>

#include "kinetic/grid/frustum_grid.h"
#include "kinetic/grid/grid_input.h"

namespace kinray::test {

using Vec = Eigen::Vector3d;

/// A mesh that owns its flightplans.
struct OwnedMesh {
  std::vector<double> times = {0.0};
  std::vector<Vec> positions;  ///< key-major
  size_t vertex_count = 0;
  std::vector<std::array<uint32_t, 3>> triangles;
  double appear = -std::numeric_limits<double>::infinity();
  double disappear = std::numeric_limits<double>::infinity();
  bool is_static = false;
};

/// A triangle per key: keys[k] = the three vertices at times[k].
inline OwnedMesh moving_triangle(std::vector<double> times, const std::vector<std::array<Vec, 3>>& keys) {
  OwnedMesh m;
  m.times = std::move(times);
  m.vertex_count = 3;
  for (const auto& key : keys)
    for (const Vec& p : key) m.positions.push_back(p);
  m.triangles = {{0, 1, 2}};
  m.is_static = keys.size() == 1;
  return m;
}

/// Positions given in image coordinates (px, py) at depth z: (px z, py z, z).
inline Vec at_depth(double px, double py, double z) { return {px * z, py * z, z}; }

struct TestScene {
  int width = 64, height = 48;
  std::deque<OwnedMesh> meshes;

  [[nodiscard]] GridInput input() const {
    GridInput in;
    in.rays = PixelRays{width, height};
    for (size_t m = 0; m < meshes.size(); ++m) {
      const OwnedMesh& o = meshes[m];
      FlightplanMesh g;
      g.id = uint32_t(m);
      g.key_times = o.times;
      g.positions = o.positions;
      g.vertex_count = o.vertex_count;
      g.triangles = o.triangles;
      g.appear = o.appear;
      g.disappear = o.disappear;
      g.is_static = o.is_static;
      in.meshes.push_back(g);
    }
    return in;
  }
};

struct BruteHit {
  uint32_t mesh = kNoGridHit, triangle = kNoGridHit;
  double depth = std::numeric_limits<double>::infinity();
};

/// Sign-rule hit of one triangle along d at positions p, or nullopt; `graze` = the smallest
/// relative edge distance |E| / (|p| |q| |d|).
inline std::optional<double> pierce(const Vec& p0, const Vec& p1, const Vec& p2, const Vec& d,
                                    double* graze = nullptr) {
  const double o = p0.dot(p1.cross(p2));
  const double e[3] = {p0.cross(p1).dot(d), p1.cross(p2).dot(d), p2.cross(p0).dot(d)};
  if (graze) {
    const double n = d.norm();
    *graze = std::min({std::abs(e[0]) / (p0.norm() * p1.norm() * n + 1e-300),
                       std::abs(e[1]) / (p1.norm() * p2.norm() * n + 1e-300),
                       std::abs(e[2]) / (p2.norm() * p0.norm() * n + 1e-300)});
  }
  if (o == 0) return std::nullopt;
  for (double v : e)
    if ((v > 0) != (o > 0) || v == 0) return std::nullopt;
  return o / (e[0] + e[1] + e[2]);
}

inline std::array<Vec, 3> triangle_at(const FlightplanMesh& mesh, uint32_t tri, double t) {
  const auto& v = mesh.triangles[tri];
  return {mesh.position(v[0], t), mesh.position(v[1], t), mesh.position(v[2], t)};
}

inline BruteHit brute_front(const GridInput& in, int i, int j, double t) {
  BruteHit best;
  const Vec d = in.rays.direction(i, j);
  for (uint32_t m = 0; m < in.meshes.size(); ++m) {
    const FlightplanMesh& mesh = in.meshes[m];
    if (!mesh.present(t)) continue;
    for (uint32_t tri = 0; tri < mesh.triangles.size(); ++tri) {
      const auto p = triangle_at(mesh, tri, t);
      const auto z = pierce(p[0], p[1], p[2], d);
      if (z && *z < best.depth) best = BruteHit{m, tri, *z};
    }
  }
  return best;
}

struct Comparison {
  size_t covered = 0;  ///< pixels the reference covers
  size_t ties = 0, real = 0;
};

/// The grid's front at now() against the brute-force reference, pixel by pixel.
inline Comparison compare_with_brute_force(const FrustumGrid& grid, const GridInput& in) {
  Comparison c;
  const double t = grid.now();
  constexpr double kTol = 1e-9;
  for (int j = 0; j < in.rays.height; ++j)
    for (int i = 0; i < in.rays.width; ++i) {
      const BruteHit ref = brute_front(in, i, j, t);
      const std::optional<GridHit> got = grid.front(i, j);
      c.covered += ref.mesh != kNoGridHit;
      const bool same = got ? (got->mesh == ref.mesh && got->triangle == ref.triangle) : ref.mesh == kNoGridHit;
      if (same) continue;
      const Vec d = in.rays.direction(i, j);
      bool tie = false;
      auto grazes = [&](uint32_t m, uint32_t tri, double* depth) {
        const auto p = triangle_at(in.meshes[m], tri, t);
        double g = 0;
        pierce(p[0], p[1], p[2], d, &g);
        const double o = p[0].dot(p[1].cross(p[2]));
        *depth = o / (p[1] - p[0]).cross(p[2] - p[0]).dot(d);
        return g < kTol;
      };
      double zg = 0, zr = ref.depth;
      if (got && grazes(got->mesh, got->triangle, &zg)) tie = true;
      if (ref.mesh != kNoGridHit && grazes(ref.mesh, ref.triangle, &zr)) tie = true;
      if (got && ref.mesh != kNoGridHit && std::abs(zg - zr) <= kTol * std::abs(zr)) tie = true;
      ++(tie ? c.ties : c.real);
    }
  return c;
}

/// Every pixel's front, row-major (kNoGridHit for background; else mesh << 24 | triangle).
inline std::vector<uint32_t> fronts(const FrustumGrid& grid) {
  std::vector<uint32_t> out;
  const int w = grid.scene().width(), h = grid.scene().height();
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const auto hit = grid.front(i, j);
      out.push_back(hit ? (hit->mesh << 24) | hit->triangle : kNoGridHit);
    }
  return out;
}

}  // namespace kinray::test
