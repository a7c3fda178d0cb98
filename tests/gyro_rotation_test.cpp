// A gyro's rotation cut between samples (estimation/gyro_rotation.h): each sample's
// rate held over the interval since the one before, counted for its overlap with the
// asked interval, held before the first and after the last; dropping what lies wholly
// before an instant.
#include "trackbed/estimation/gyro_rotation.h"

#include <cmath>
#include <deque>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

namespace trackbed::estimation {
namespace {

/// The rotation vector of R [rad].
Eigen::Vector3d Log(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

/// Samples every 5 ms from 0 to 1 s: 0.5 rad/s about z until 0.5 s, then 0.2 rad/s
/// about x (the sample at 0.5 s still the first rate, held over (0.495, 0.5]).
std::deque<GyroInterval> StepRate() {
  std::deque<GyroInterval> g;
  for (int k = 1; k <= 200; ++k) {
    const double t = 0.005 * k;
    const Eigen::Vector3d rate =
        t <= 0.5 + 1e-12 ? Eigen::Vector3d(0.0, 0.0, 0.5) : Eigen::Vector3d(0.2, 0.0, 0.0);
    g.push_back({t - 0.005, t, rate});
  }
  return g;
}

TEST(GyroRotationTest, CutsTheHeldRatesBetweenSamples) {
  const std::deque<GyroInterval> g = StepRate();
  // Within the first rate: 0.5 rad/s over 0.1008 s.
  EXPECT_NEAR((Log(IntegrateGyro(g, 0.1025, 0.2033)) - Eigen::Vector3d(0, 0, 0.0504)).norm(), 0.0,
              1e-12);
  // Across the step: 0.5 rad/s over 0.0133 s, then 0.2 rad/s about x over 0.0217 s.
  const Eigen::Matrix3d expected =
      Eigen::AngleAxisd(0.5 * 0.0133, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
      Eigen::AngleAxisd(0.2 * 0.0217, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_LT((IntegrateGyro(g, 0.4867, 0.5217) - expected).norm(), 1e-12);
}

TEST(GyroRotationTest, HoldsTheRatesBeyondTheSamples) {
  const std::deque<GyroInterval> g = StepRate();
  // 1 s is the last sample: 0.2 rad/s held 3 ms past it.
  EXPECT_NEAR((Log(IntegrateGyro(g, 0.998, 1.003)) - Eigen::Vector3d(0.001, 0, 0)).norm(), 0.0,
              1e-12);
  // Before the first interval (0, 0.005]: its rate held from −0.01 s.
  EXPECT_NEAR((Log(IntegrateGyro(g, -0.01, 0.005)) - Eigen::Vector3d(0, 0, 0.0075)).norm(), 0.0,
              1e-12);
  EXPECT_TRUE(IntegrateGyro({}, 0.0, 1.0).isIdentity());
  EXPECT_TRUE(IntegrateGyro(g, 0.3, 0.3).isIdentity());
}

TEST(GyroRotationTest, DropsOnlyWhatLiesWhollyBefore) {
  std::deque<GyroInterval> g = StepRate();
  const Eigen::Matrix3d before = IntegrateGyro(g, 0.1025, 0.2033);
  DropGyroBefore(0.1025, &g);
  EXPECT_DOUBLE_EQ(g.front().t1_s, 0.105);  // (0.1, 0.105] still reaches past 0.1025
  EXPECT_LT((IntegrateGyro(g, 0.1025, 0.2033) - before).norm(), 1e-15);
  DropGyroBefore(2.0, &g);
  EXPECT_TRUE(g.empty());
}

}  // namespace
}  // namespace trackbed::estimation
