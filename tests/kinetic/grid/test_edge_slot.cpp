#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "kinetic/grid/coverage_rule.h"
#include "kinetic/grid/edge_slot.h"
#include "util/pixel_rays.h"

namespace kinray {
namespace {

// The slot and the watched signs as locate_boundary found them before the certified step: the
// bisection of SlotCircle::locate over edge_sign, then edge_sign at the watched columns.
EdgeSlot bisected(const EdgeNormal& n, const SlotCircle& columns, const PixelRays& rays, double y,
                  double s) {
  return bisected_edge_slot(columns, [&](int c) { return edge_sign(n, rays.x(c), y, s); });
}

/// locate_edge_slot finds what the bisection finds.
void expect_located_as_bisected(const EdgeNormal& n, const SlotCircle& columns,
                                const PixelRays& rays, double y, double s) {
  const EdgeSlot got = locate_edge_slot(
      n, columns, [&](int c) { return rays.x(c); }, y, s);
  const EdgeSlot want = bisected(n, columns, rays, y, s);
  EXPECT_EQ(got.slot, want.slot);
  EXPECT_EQ(got.sign_lo, want.sign_lo);
  EXPECT_EQ(got.sign_hi, want.sign_hi);
}

struct Draw {
  EdgeNormal n;
  double y, s;
};

// Edge normals of three kinds: generic motions; small integer motions at dyadic times, whose
// edge functions vanish exactly at some pixel centres (the perturbed sign decides there); and
// nearly constant edge functions along the row (a tiny x component), whose computed signs need
// not be one step. The row is a pixel row; the point is often inside the image.
Draw draw(std::mt19937_64& rng, const PixelRays& rays) {
  std::uniform_real_distribution<double> u(-10, 10);
  std::uniform_int_distribution<int> small(-3, 3), kind(0, 2), row(0, rays.height - 1);
  Draw d;
  d.y = rays.y(row(rng));
  PointMotion p, q;
  const int k = kind(rng);
  if (k == 1) {
    p.a = Eigen::Vector3d(small(rng), small(rng), small(rng));
    p.b = Eigen::Vector3d(small(rng), small(rng), small(rng));
    q.a = Eigen::Vector3d(small(rng), small(rng), small(rng));
    q.b = Eigen::Vector3d(small(rng), small(rng), small(rng));
    d.s = std::ldexp(double(small(rng)), -2);
  } else {
    p.a = Eigen::Vector3d(u(rng), u(rng), u(rng) + 20);
    p.b = Eigen::Vector3d(u(rng), u(rng), u(rng));
    q.a = Eigen::Vector3d(u(rng), u(rng), u(rng) + 20);
    q.b = Eigen::Vector3d(u(rng), u(rng), u(rng));
    d.s = u(rng) / 10;
  }
  d.n = edge_normal(p, q);
  if (k == 2) {
    const double tiny = std::ldexp(1.0, -40 - int(rng() % 20));
    d.n.c0.x() *= tiny;
    d.n.c1.x() *= tiny;
    d.n.c2.x() *= tiny;
  }
  return d;
}

// locate_edge_slot must give exactly the bisection's slot and signs, wherever the certified step
// answers and wherever it leaves the answer to the bisection; and it must answer most generic
// draws itself (else it buys nothing).
TEST(EdgeSlot, IsTheBisectionsSlotAndSigns) {
  std::mt19937_64 rng(14);
  for (const auto& [w, h] : {std::pair{1, 1}, std::pair{2, 3}, std::pair{7, 5}, std::pair{96, 72},
                             std::pair{512, 512}}) {
    const PixelRays rays{w, h};
    SlotCircle columns;
    columns.count = w;
    int stepped = 0, inside = 0;
    for (int i = 0; i < 20000; ++i) {
      const Draw d = draw(rng, rays);
      const EdgeSlot got = locate_edge_slot(
          d.n, columns, [&](int c) { return rays.x(c); }, d.y, d.s);
      const EdgeSlot want = bisected(d.n, columns, rays, d.y, d.s);
      ASSERT_EQ(got.slot, want.slot) << w << "x" << h << " draw " << i;
      ASSERT_EQ(got.sign_lo, want.sign_lo) << w << "x" << h << " draw " << i;
      ASSERT_EQ(got.sign_hi, want.sign_hi) << w << "x" << h << " draw " << i;
      if (w > 1 && want.slot != 0) {
        ++inside;
        const EdgeOnRay first(d.n, rays.x(0), d.y, d.s), last(d.n, rays.x(w - 1), d.y, d.s);
        const std::optional<EdgeSlot> step =
            detail::certified_step(d.n, w, d.y, d.s, first.sign(d.n, d.y, d.s), first, last,
                                   [&](int c) { return EdgeOnRay(d.n, rays.x(c), d.y, d.s); });
        if (step) {
          ++stepped;
          EXPECT_EQ(step->slot, want.slot);
        }
      }
    }
    if (w >= 96) {
      EXPECT_GT(stepped, inside / 2) << w << "x" << h;
    }
  }
}

// A column exactly on the point (a zero of the edge function, decided by the perturbation) and
// a nearly constant edge function are left to the bisection.
TEST(EdgeSlot, LeavesUncertainColumnsToTheBisection) {
  const PixelRays rays{8, 8};
  SlotCircle columns;
  columns.count = 8;
  const double y = rays.y(3), x = rays.x(5);
  // E = x_c - x: exactly 0 at column 5.
  EdgeNormal n;
  n.c0 = Eigen::Vector3d(1, 0, -x);
  const EdgeOnRay first(n, rays.x(0), y, 0.0), last(n, rays.x(7), y, 0.0);
  auto ray = [&](int c) { return EdgeOnRay(n, rays.x(c), y, 0.0); };
  EXPECT_FALSE(detail::certified_step(n, 8, y, 0.0, -1, first, last, ray));
  expect_located_as_bisected(n, columns, rays, y, 0.0);
  // E = 1e-17 (x_c - x) + 1 - s at s = 1: the slope is far below the rounding of the terms, so
  // the computed signs need not be one step.
  n = EdgeNormal{};
  n.c0 = Eigen::Vector3d(1e-17, 0, 1 - 1e-17 * x);
  n.c1 = Eigen::Vector3d(0, 0, -1);
  const EdgeOnRay f(n, rays.x(0), y, 1.0), l(n, rays.x(7), y, 1.0);
  if (f.sign(n, y, 1.0) != l.sign(n, y, 1.0)) {
    EXPECT_FALSE(detail::certified_step(n, 8, y, 1.0, f.sign(n, y, 1.0), f, l,
                                        [&](int c) { return EdgeOnRay(n, rays.x(c), y, 1.0); }));
  }
  expect_located_as_bisected(n, columns, rays, y, 1.0);
}

// boundary_front_sign is sign_plus of boundary_depth oriented by q's row side, as the band built
// it from polynomials: generic motions, and small integer motions at dyadic times, where the
// depth, the side or both vanish exactly (the polynomial path decides there).
TEST(EdgeSlot, BoundaryFrontSignIsThePolynomialsSign) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> u(-10, 10);
  std::uniform_int_distribution<int> small(-2, 2);
  const PixelRays rays{16, 16};
  for (int i = 0; i < 100000; ++i) {
    PointMotion p, q;
    double s, y = rays.y(int(rng() % 16));
    if (i % 2 == 0) {
      p.a = Eigen::Vector3d(u(rng), u(rng), u(rng));
      p.b = Eigen::Vector3d(u(rng), u(rng), u(rng));
      q.a = Eigen::Vector3d(u(rng), u(rng), u(rng));
      q.b = Eigen::Vector3d(u(rng), u(rng), u(rng));
      s = u(rng);
    } else {
      p.a = Eigen::Vector3d(small(rng), small(rng), small(rng));
      p.b = Eigen::Vector3d(small(rng), small(rng), small(rng));
      q.a = Eigen::Vector3d(small(rng), small(rng), small(rng));
      q.b = Eigen::Vector3d(small(rng), small(rng), small(rng));
      s = std::ldexp(double(small(rng)), -1);
      y = std::ldexp(double(small(rng)), -2);
    }
    const Polynomial z = boundary_depth(p, q, y);
    const int want = sign_plus(sign_plus(row_side(q, y), s) > 0 ? z : -z, s);
    ASSERT_EQ(boundary_front_sign(p, q, y, s), want) << "draw " << i;
  }
}

}  // namespace
}  // namespace kinray
