// Range scan → obstacle circles: synthetic scans of known circles and a wall, cast
// analytically here (the simulator's ray tests are not part of the navigation library).
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "trackbed/navigation/scan_clustering.h"

namespace trackbed::navigation {
namespace {

// Distance along a ray from `origin` in direction `dir` (unit) to a circle, or +inf.
double RayCircle(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, const Circle& c) {
  const Eigen::Vector2d oc = origin - c.centre;
  const double b = oc.dot(dir), q = oc.squaredNorm() - c.radius_m * c.radius_m;
  const double disc = b * b - q;
  if (disc < 0) return std::numeric_limits<double>::infinity();
  const double t = -b - std::sqrt(disc);
  return t > 0 ? t : std::numeric_limits<double>::infinity();
}

// 360 beams over a full turn, sensor frame, from a sensor at `pose` seeing `circles`.
RangeScan CastScan(const Pose2& pose, const std::vector<Circle>& circles, double noise_m,
                   std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_m);
  RangeScan scan;
  scan.max_range_m = 8.0;
  for (int i = 0; i < 360; ++i) {
    const double a = -M_PI + 2.0 * M_PI * i / 360;
    const Eigen::Vector2d dir(std::cos(pose.yaw + a), std::sin(pose.yaw + a));
    double r = std::numeric_limits<double>::infinity();
    for (const Circle& c : circles) r = std::min(r, RayCircle({pose.x, pose.y}, dir, c));
    if (std::isfinite(r) && noise_m > 0) r += noise(rng);
    scan.angles_rad.push_back(a);
    scan.ranges_m.push_back(r < scan.max_range_m ? r : scan.max_range_m);
  }
  return scan;
}

const Circle* Nearest(const std::vector<Circle>& found, const Eigen::Vector2d& p) {
  const Circle* best = nullptr;
  for (const Circle& c : found) {
    if (!best || (c.centre - p).norm() < (best->centre - p).norm()) best = &c;
  }
  return best;
}

TEST(ScanClusteringTest, RecoversTwoKnownCircles) {
  const std::vector<Circle> truth = {{{3.0, 1.0}, 0.4}, {{-1.0, 4.0}, 0.3}};
  const Pose2 sensor{0.5, -0.5, 0.7};
  const std::vector<Circle> found = ClusterScan(CastScan(sensor, truth, 0.0, 1), sensor);
  ASSERT_EQ(found.size(), 2u);
  for (const Circle& t : truth) {
    const Circle* c = Nearest(found, t.centre);
    EXPECT_LT((c->centre - t.centre).norm(), 0.02);
    EXPECT_NEAR(c->radius_m, t.radius_m, 0.02);
  }
}

TEST(ScanClusteringTest, NoisyHitsGiveCirclesThatStillCoverTheObstacles) {
  const std::vector<Circle> truth = {{{3.0, 1.0}, 0.4}, {{-1.0, 4.0}, 0.3}};
  const Pose2 sensor{0.5, -0.5, 0.7};
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const std::vector<Circle> found = ClusterScan(CastScan(sensor, truth, 0.01, seed), sensor);
    ASSERT_EQ(found.size(), 2u) << "seed " << seed;
    for (const Circle& t : truth) {
      const Circle* c = Nearest(found, t.centre);
      EXPECT_LT((c->centre - t.centre).norm(), 0.15) << "seed " << seed;
      // The near side seen by the sensor is inside the found circle.
      const Eigen::Vector2d towards = (Eigen::Vector2d(sensor.x, sensor.y) - t.centre).normalized();
      EXPECT_LE((t.centre + t.radius_m * towards - c->centre).norm(), c->radius_m + 0.03);
    }
  }
}

TEST(ScanClusteringTest, AWallBecomesAChainNoFartherApartThanDmax) {
  std::vector<Circle> wall;  // a dense chain is a wall to the scanner
  for (int k = 0; k <= 120; ++k) wall.push_back({{2.0, -3.0 + 0.05 * k}, 0.05});
  const Pose2 sensor{0, 0, 0};
  const RangeScan scan = CastScan(sensor, wall, 0.0, 1);
  const std::vector<Circle> found = ClusterScan(scan, sensor);
  ASSERT_GE(found.size(), 6u);
  for (std::size_t k = 1; k < found.size(); ++k) {
    EXPECT_LE((found[k].centre - found[k - 1].centre).norm(), 1.0 + 1e-9);
  }
  // Every hit is covered by some circle.
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (!(scan.ranges_m[i] < scan.max_range_m)) continue;
    const Eigen::Vector2d hit = scan.ranges_m[i] * Eigen::Vector2d(std::cos(scan.angles_rad[i]),
                                                                   std::sin(scan.angles_rad[i]));
    bool covered = false;
    for (const Circle& c : found) covered = covered || (hit - c.centre).norm() <= c.radius_m + 1e-9;
    EXPECT_TRUE(covered) << "beam " << i;
  }
}

TEST(ScanClusteringTest, EmptyScanAndMismatchedSizes) {
  RangeScan empty;
  empty.angles_rad = {0.0, 0.1};
  empty.ranges_m = {8.0, std::numeric_limits<double>::infinity()};
  EXPECT_TRUE(ClusterScan(empty, {}).empty());
  empty.ranges_m.pop_back();
  EXPECT_THROW(ClusterScan(empty, {}), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::navigation
