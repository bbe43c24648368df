// BART's Kochanek-Bartels splines against closed forms: with tension, continuity and bias 0 the
// position spline is a Catmull-Rom spline (exact on linear motion, the (-1, 9, 9, -1) / 16 rule at
// the middle of uniform pieces), it passes through its inner keys and is clamped outside them;
// a rotation spline through equal steps about one axis turns uniformly about that axis.
#include <gtest/gtest.h>

#include <cmath>
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
