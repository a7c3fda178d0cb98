// The plots' decimated paths and series: every point while under the capacity, a
// bounded count on a long run, the path's shape kept within the stated step.
#include "trackbed/runner/plot_decimation.h"

#include <cmath>

#include <gtest/gtest.h>

namespace trackbed::runner {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A pose on a circle of radius 5 m, driven at 0.4 m/s: s metres along it.
Eigen::Isometry3d OnCircle(double s) {
  const double a = s / 5.0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() << 5.0 * std::cos(a), 5.0 * std::sin(a), 0.3;
  T.linear() = Eigen::AngleAxisd(a + 0.5 * kPi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

TEST(DecimatedPathTest, KeepsEveryPoseUnderTheCapacity) {
  DecimatedPath path(100);
  for (int k = 0; k < 99; ++k) path.Add(0.1 * k, OnCircle(0.04 * k));
  ASSERT_EQ(path.size(), 99u);
  const estimation::Trajectory poses = path.Poses();
  ASSERT_EQ(poses.size(), 99u);
  EXPECT_EQ(poses[42].t_s, 0.1 * 42);
  EXPECT_EQ(poses[42].T_world_body.translation().head<2>(),
            OnCircle(0.04 * 42).translation().head<2>());
  EXPECT_EQ(path.step_m(), 0.0);
}

TEST(DecimatedPathTest, LongRunStaysBoundedAndOnThePath) {
  DecimatedPath path(1000);
  const int n = 200000;  // 8000 m: 255 laps of the circle, 4 cm apart
  std::size_t largest = 0;
  for (int k = 0; k < n; ++k) {
    path.Add(0.1 * k, OnCircle(0.04 * k));
    largest = std::max(largest, path.size());
  }
  EXPECT_LT(largest, 1000u);
  EXPECT_GT(path.step_m(), 0.05);
  const std::vector<Eigen::Vector2d> points = path.Points();
  ASSERT_GE(points.size(), 3u);
  // The first and the latest pose are kept.
  EXPECT_EQ(points.front(), OnCircle(0.0).translation().head<2>());
  EXPECT_EQ(points.back(), OnCircle(0.04 * (n - 1)).translation().head<2>());
  for (const Eigen::Vector2d& p : points) EXPECT_NEAR(p.norm(), 5.0, 1e-9);
  // Consecutive points are at most the step of path apart, or the turn threshold's arc
  // (5 m × turn), one sample more (0.04 m).
  const double arc = std::min(path.step_m(), 5.0 * path.turn_rad()) + 0.04 + 1e-9;
  for (std::size_t k = 1; k + 1 < points.size(); ++k)
    EXPECT_LE((points[k] - points[k - 1]).norm(), arc);
  EXPECT_GT(points.size(), 400u);  // 8000 m at the final spacing
}

TEST(DecimatedPathTest, StandingStillAddsNothingOnceThinned) {
  DecimatedPath path(100);
  for (int k = 0; k < 10000; ++k) path.Add(0.1 * k, OnCircle(0.0));
  EXPECT_LE(path.size(), 100u);
  EXPECT_EQ(path.Points().size(), 2u);  // the first pose and the latest
}

TEST(DecimatedSeriesTest, StrideDoublesAtTheCapacity) {
  DecimatedSeries s(8);
  for (int k = 0; k < 7; ++k) s.Add(k, 10.0 * k);
  EXPECT_EQ(s.size(), 7u);
  for (int k = 7; k < 1000; ++k) s.Add(k, 10.0 * k);
  EXPECT_LT(s.size(), 8u);
  // What is kept is every stride-th sample from the first.
  const double stride = s.points()[1].x() - s.points()[0].x();
  EXPECT_EQ(stride, 256.0);
  for (std::size_t k = 0; k < s.size(); ++k) {
    EXPECT_EQ(s.points()[k].x(), stride * static_cast<double>(k));
    EXPECT_EQ(s.points()[k].y(), 10.0 * s.points()[k].x());
  }
}

}  // namespace
}  // namespace trackbed::runner
