// BART's Kochanek-Bartels splines against closed forms: with tension, continuity and bias 0 the
// position spline is a Catmull-Rom spline (exact on linear motion, the (-1, 9, 9, -1) / 16 rule at
// the middle of uniform pieces), it passes through its inner keys and is clamped outside them;
// a rotation spline through equal steps about one axis turns uniformly about that axis.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <vector>

#include "scenes/aff_spline.h"

namespace kinray {
namespace {

using Eigen::Vector3d;

std::vector<SplineKey> position_keys(const std::vector<double>& times,
                                     const std::vector<Vector3d>& values) {
  std::vector<SplineKey> keys;
  for (size_t i = 0; i < times.size(); ++i) keys.push_back({times[i], values[i]});
  return keys;
}

TEST(AffSpline, CatmullRomIsExactOnLinearMotion) {
  // Non-uniform key times on a straight line at constant speed: the adjusted tangents keep it so.
  const std::vector<double> times = {-1, 0, 0.5, 2, 3, 3.5};
  std::vector<Vector3d> values;
  for (double t : times) values.push_back(Vector3d(1, 2, 3) + t * Vector3d(0.5, -1, 2));
  const PositionSpline spline(position_keys(times, values));
  for (double t = 0; t <= 3; t += 0.125) {
    const Vector3d expected = Vector3d(1, 2, 3) + t * Vector3d(0.5, -1, 2);
    EXPECT_NEAR((spline.at(t) - expected).norm(), 0, 1e-12) << "t=" << t;
  }
}

TEST(AffSpline, UniformMiddleFollowsTheCatmullRomRule) {
  const std::vector<Vector3d> p = {{0, 0, 0}, {1, 3, 0}, {2, 1, 5}, {4, 4, -2}};
  const PositionSpline spline(position_keys({0, 1, 2, 3}, p));
  const Vector3d expected = (-p[0] + 9 * p[1] + 9 * p[2] - p[3]) / 16;
  EXPECT_NEAR((spline.at(1.5) - expected).norm(), 0, 1e-12);
}

TEST(AffSpline, PassesThroughInnerKeysAndClampsOutside) {
  const std::vector<Vector3d> p = {{0, 0, 0}, {1, 3, 0}, {2, 1, 5}, {4, 4, -2}, {5, 0, 1}};
  std::vector<SplineKey> keys = position_keys({0, 1, 2.5, 3, 4}, p);
  keys[2].tension = 0.5, keys[2].continuity = -0.3, keys[3].bias = 0.7;
  const PositionSpline spline(keys);
  EXPECT_EQ(spline.begin(), 1);
  EXPECT_EQ(spline.end(), 3);
  EXPECT_NEAR((spline.at(1) - p[1]).norm(), 0, 1e-12);
  EXPECT_NEAR((spline.at(2.5) - p[2]).norm(), 0, 1e-12);
  EXPECT_NEAR((spline.at(3) - p[3]).norm(), 0, 1e-12);
  EXPECT_EQ(spline.at(-5), spline.at(1));
  EXPECT_EQ(spline.at(10), spline.at(3));
}

/// Kochanek and Bartels (SIGGRAPH 1984), written from the paper: the cubic Hermite curve between
/// keys i and i + 1 whose end tangents are the outgoing ("destination") tangent TD_i and the
/// incoming ("source") tangent TS_{i+1}, each built from the chords around its key with that
/// key's tension, continuity and bias and scaled for unequal key spacing (the paper's section 4).
Vector3d kochanek_bartels(const std::vector<SplineKey>& k, size_t i, double u) {
  const auto chord = [&](size_t a) { return Vector3d(k[a + 1].value - k[a].value); };
  const SplineKey &ki = k[i], &kj = k[i + 1];
  const double before = ki.time - k[i - 1].time, span = kj.time - ki.time,
               after = k[i + 2].time - kj.time;
  const Vector3d td =
      (0.5 * (1 - ki.tension) * (1 + ki.continuity) * (1 + ki.bias)) * chord(i - 1) +
      (0.5 * (1 - ki.tension) * (1 - ki.continuity) * (1 - ki.bias)) * chord(i);
  const Vector3d ts = (0.5 * (1 - kj.tension) * (1 - kj.continuity) * (1 + kj.bias)) * chord(i) +
                      (0.5 * (1 - kj.tension) * (1 + kj.continuity) * (1 - kj.bias)) * chord(i + 1);
  const Vector3d out = td * (2 * span / (before + span)), in = ts * (2 * span / (span + after));
  const double h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u,
               h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
  return h00 * ki.value + h10 * out + h01 * kj.value + h11 * in;
}

TEST(AffSpline, BetweenKeysFollowsKochanekAndBartels) {
  // Unequal spacing and a different tension, continuity and bias at every key.
  const std::vector<Vector3d> p = {{0, 0, 0},  {1, 3, 0}, {2, 1, 5},
                                   {4, 4, -2}, {5, 0, 1}, {7, 2, 2}};
  std::vector<SplineKey> keys = position_keys({0, 1, 2.5, 3, 4.5, 5}, p);
  const double tcb[6][3] = {{0.2, 0.1, -0.3},  {0.5, -0.3, 0.2}, {-0.4, 0.6, 0.7},
                            {0.1, -0.8, -0.5}, {0.3, 0.2, 0.4},  {0, 0, 0}};
  for (size_t i = 0; i < keys.size(); ++i)
    std::tie(keys[i].tension, keys[i].continuity, keys[i].bias) =
        std::tuple{tcb[i][0], tcb[i][1], tcb[i][2]};
  const PositionSpline spline(keys);
  int checked = 0;
  for (size_t i = 1; i + 2 < keys.size(); ++i)
    for (double u : {0.1, 0.25, 0.5, 0.7, 0.9}) {
      const double t = keys[i].time + u * (keys[i + 1].time - keys[i].time);
      EXPECT_NEAR((spline.at(t) - kochanek_bartels(keys, i, u)).norm(), 0, 1e-12)
          << "piece " << i << " u=" << u;
      ++checked;
    }
  EXPECT_EQ(checked, 15);
}

TEST(AffSpline, RotationStepsAboutOneAxisTurnUniformly) {
  std::vector<SplineKey> keys;
  const Vector3d axis = Vector3d(1, 2, 2) / 3;
  for (int i = 0; i < 6; ++i) {
    SplineKey key;
    key.time = i;
    key.value = axis * 7;                // not unit: normalized by the spline
    key.angle_degrees = 30.0 * i + 400;  // beyond a full turn: only the rotation matters
    keys.push_back(key);
  }
  const RotationSpline spline(keys);
  for (double t = 1; t <= 4; t += 0.25) {
    const Eigen::Quaterniond expected(Eigen::AngleAxisd((30.0 * t + 400) * M_PI / 180, axis));
    EXPECT_NEAR(spline.at(t).angularDistance(expected), 0, 1e-9) << "t=" << t;
  }
  // Clamped outside [t_1, t_{n-2}].
  EXPECT_NEAR(spline.at(0).angularDistance(spline.at(1)), 0, 1e-12);
  EXPECT_NEAR(spline.at(9).angularDistance(spline.at(4)), 0, 1e-12);
}

TEST(AffSpline, RotationPassesThroughKeysOnDifferentAxes) {
  std::vector<SplineKey> keys;
  const std::vector<Vector3d> axes = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}};
  const std::vector<double> angles = {10, -80, 200, 45,
                                      300};  // 200 degrees: the flip to the near side
  for (size_t i = 0; i < axes.size(); ++i) {
    SplineKey key;
    key.time = double(i) * 1.5;
    key.value = axes[i];
    key.angle_degrees = angles[i];
    key.tension = 0.2;
    keys.push_back(key);
  }
  const RotationSpline spline(keys);
  for (size_t i = 1; i + 1 < axes.size(); ++i) {
    const Eigen::Quaterniond expected(
        Eigen::AngleAxisd(angles[i] * M_PI / 180, axes[i].normalized()));
    EXPECT_NEAR(spline.at(keys[i].time).angularDistance(expected), 0, 1e-9) << "key " << i;
  }
  EXPECT_NEAR(spline.at(2.0).norm(), 1, 1e-12);
}

}  // namespace
}  // namespace kinray
