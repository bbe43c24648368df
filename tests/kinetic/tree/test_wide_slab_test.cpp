// The 4-wide float slab test keeps every box a ray meets, even by a single point of its boundary,
// drops the boxes a ray clearly misses, and drops empty slots whatever the ray.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "kinetic/tree/wide_slab_test.h"

namespace kinray {
namespace {

constexpr float kInf = INFINITY;

struct Boxes {
  alignas(16) float bound[6][4];
  Boxes() {
    for (int k = 0; k < 4; ++k) set(k, {kInf, kInf, kInf, -kInf, -kInf, -kInf});
  }
  void set(int k, const std::array<float, 6>& b) {
    for (int r = 0; r < 6; ++r) bound[r][k] = b[size_t(r)];
  }
};

std::array<float, 6> random_box(std::mt19937& rng) {
  std::uniform_real_distribution<float> c(-100, 100), size(0.001f, 20);
  std::array<float, 6> b;
  for (int a = 0; a < 3; ++a) {
    b[size_t(a)] = c(rng);
    b[size_t(a) + 3] = b[size_t(a)] + size(rng);
  }
  return b;
}

TEST(WideSlabTest, KeepsEveryBoxARayTouchesAtOnePointOfItsBoundary) {
  // The ray passes exactly through a point of the box's boundary (a face, an edge or a corner):
  // the direction's components are 0 or powers of two and so is s, so origin = P - s d is exact.
  std::mt19937 rng(5);
  int kept = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const std::array<float, 6> b = random_box(rng);
    Eigen::Vector3d p, d;
    for (int a = 0; a < 3; ++a) {
      const int where = int(rng() % 3);  // on the low side, the high side, or inside
      p[a] = where == 0   ? b[size_t(a)]
             : where == 1 ? b[size_t(a) + 3]
                          : 0.5 * (double(b[size_t(a)]) + double(b[size_t(a) + 3]));
      const int kind = int(rng() % 4);
      d[a] = kind == 0 ? 0.0 : std::ldexp(rng() % 2 != 0 ? 1.0 : -1.0, int(rng() % 40) - 20);
    }
    if (d.isZero()) d.x() = 1;
    const double s = std::ldexp(1.0, int(rng() % 20) - 10);
    const Eigen::Vector3d origin = p - s * d;
    ASSERT_EQ(origin + s * d, p);  // exact
    Boxes boxes;
    boxes.set(int(trial % 4), b);
    float entry[4];
    for (double s_max : {2 * s, double(INFINITY)}) {
      const WideRay ray(origin, d, 0, s_max);
      ASSERT_NE(ray.test(boxes.bound, entry) & (1 << (trial % 4)), 0)
          << "trial " << trial << ": the ray meets the box at s = " << s;
      EXPECT_LE(entry[trial % 4], ray.scaled_up(s));
    }
    ++kept;
  }
  EXPECT_EQ(kept, 200000);
}

TEST(WideSlabTest, AgreesWithAnExtendedPrecisionTestAwayFromTies) {
  // Random rays and boxes: where the long double slab test says "meets" or "misses" by more
  // than 1e-6 of the parameters, the wide test answers the same.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-150, 150);
  int meets = 0, misses = 0;
  for (int trial = 0; trial < 100000; ++trial) {
    const std::array<float, 6> b = random_box(rng);
    // Aimed at a point of the box grown by half its size on every side: about half meet it.
    Eigen::Vector3d target;
    for (int a = 0; a < 3; ++a) {
      const double lo = b[size_t(a)], size = b[size_t(a) + 3] - lo;
      target[a] = lo - 0.5 * size + 2 * size * std::uniform_real_distribution<double>(0, 1)(rng);
    }
    const Eigen::Vector3d origin(u(rng), u(rng), u(rng)), d = target - origin;
    long double lo = 0, hi = 1e30L;
    for (int a = 0; a < 3; ++a) {
      const long double t0 = ((long double)b[size_t(a)] - origin[a]) / d[a];
      const long double t1 = ((long double)b[size_t(a) + 3] - origin[a]) / d[a];
      lo = std::max(lo, std::min(t0, t1));
      hi = std::min(hi, std::max(t0, t1));
    }
    const long double slack = 1e-6L * (1 + std::fabs(lo) + std::fabs(hi));
    if (std::fabs(lo - hi) < slack) continue;
    Boxes boxes;
    boxes.set(1, b);
    float entry[4];
    const bool kept = (WideRay(origin, d, 0, 1e30).test(boxes.bound, entry) & 2) != 0;
    EXPECT_EQ(kept, lo < hi) << "trial " << trial;
    ++(lo < hi ? meets : misses);
  }
  EXPECT_GT(meets, 1000);
  EXPECT_GT(misses, 1000);
}

TEST(WideSlabTest, DropsEmptySlotsAndKeepsBoxesAlongAnAxisParallelRay) {
  Boxes boxes;
  boxes.set(2, {0, 0, 0, 1, 1, 1});
  float entry[4];
  // Along z only, starting on the box's x and y faces: x and y are ignored (no division by 0),
  // z decides. Only slot 2 is a box.
  const WideRay along_z(Eigen::Vector3d(0, 1, -5), Eigen::Vector3d(0, 0, 1), 0, INFINITY);
  EXPECT_EQ(along_z.test(boxes.bound, entry), 1 << 2);
  EXPECT_FLOAT_EQ(entry[2], 5.0f * (1 - 0x1p-20f));
  // The same ray pointing away: it leaves the box's slab behind.
  const WideRay away(Eigen::Vector3d(0, 1, -5), Eigen::Vector3d(0, 0, -1), 0, INFINITY);
  EXPECT_EQ(away.test(boxes.bound, entry), 0);
  // Ending before the box: s_max = 4 < 5.
  const WideRay short_ray(Eigen::Vector3d(0.5, 0.5, -5), Eigen::Vector3d(0, 0, 1), 0, 4);
  EXPECT_EQ(short_ray.test(boxes.bound, entry), 0);
  // Its margins assume an entry that is never negative: a ray starting behind its origin is
  // refused.
  EXPECT_THROW(WideRay(Eigen::Vector3d(0.5, 0.5, -5), Eigen::Vector3d(0, 0, 1), -1, 4),
               std::invalid_argument);
}

}  // namespace
}  // namespace kinray
