// Closed-loop navigation on the simulated tracked robot (docs/navigation.md): the range sensor
// against Bullet, the chassis–obstacle clearance against hand-computed cases, and a
// short course driven on the fused estimate with success judged by ground truth.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "trackbed/robot/range_sensor.h"
#include "trackbed/runner/footprint_clearance.h"
#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/world.h"

namespace trackbed {
namespace {

sim::StaticObject Cylinder(double x, double y, double radius) {
  sim::StaticObject o;
  o.shape = sim::StaticObject::Shape::kCylinder;
  o.kind = "tree";
  o.center_m = {x, y};
  o.radius_m = radius;
  o.height_m = 2.0;
  o.base_z_m = 0.0;
  return o;
}

TEST(RangeSensorTest, SeesACylinderAtItsDistanceAndNothingElse) {
  sim::TerrainOptions terrain;  // flat
  const sim::World world({}, sim::Terrain(terrain, 1), {Cylinder(3.0, 0.0, 0.2)});
  robot::RangeSensorOptions o;
  o.enabled = true;
  const robot::RangeSensor sensor(o, 7);
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  T_world_body.translation() = Eigen::Vector3d(0.0, 0.0, 0.2);
  const robot::RangeScanSample scan = sensor.Scan(world, T_world_body, 0.0, 0);
  ASSERT_EQ(scan.ranges_m.size(), 360u);
  // Beam 0 looks straight ahead from x = 0.2 m: the surface is at 2.8 − 0.2 = 2.6 m.
  EXPECT_NEAR(scan.ranges_m[0], 2.6, 5 * o.noise_std_m);
  EXPECT_TRUE(std::isinf(scan.ranges_m[90]));   // left: nothing
  EXPECT_TRUE(std::isinf(scan.ranges_m[180]));  // behind: nothing (the ground is not seen)
  // The same scan index gives the same noise; another index other noise.
  EXPECT_EQ(sensor.Scan(world, T_world_body, 0.0, 0).ranges_m, scan.ranges_m);
  EXPECT_NE(sensor.Scan(world, T_world_body, 0.1, 1).ranges_m[0], scan.ranges_m[0]);
}

TEST(ChassisClearanceTest, BoxAgainstCirclesAndBoxesByHand) {
  const Eigen::Vector2d hull(0.7, 0.42);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  EXPECT_NEAR(runner::ChassisClearance(T, hull, {Cylinder(1.0, 0.0, 0.1)}), 1.0 - 0.35 - 0.1,
              1e-12);
  T.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NEAR(runner::ChassisClearance(T, hull, {Cylinder(1.0, 0.0, 0.1)}), 1.0 - 0.21 - 0.1,
              1e-12);
  // Diagonal: from the corner (0.35, 0.21) to the centre (1, 1), minus the radius.
  T = Eigen::Isometry3d::Identity();
  EXPECT_NEAR(runner::ChassisClearance(T, hull, {Cylinder(1.0, 1.0, 0.1)}),
              std::hypot(0.65, 0.79) - 0.1, 1e-12);
  EXPECT_LT(runner::ChassisClearance(T, hull, {Cylinder(0.3, 0.0, 0.1)}), 0.0);
  sim::StaticObject box;  // a bench 1.5 m × 0.45 m, 1 m ahead of the nose, across
  box.center_m = {0.35 + 1.0 + 0.225, 0.0};
  box.size_m = {1.5, 0.45, 0.45};
  box.yaw_rad = M_PI / 2;
  EXPECT_NEAR(runner::ChassisClearance(T, hull, {box}), 1.0, 1e-9);
  box.center_m.x() = 0.5;
  EXPECT_LT(runner::ChassisClearance(T, hull, {box}), 0.0);
  sim::StaticObject poster = box;  // dressing does not count
  poster.collides = false;
  EXPECT_TRUE(std::isinf(runner::ChassisClearance(T, hull, {poster})));
}

// Seeds 1-4 on grass (turf, μ 0.5). Every run must reach the goal by its own (fused)
// estimate, touch nothing and avoid the tree by a sub-goal. Success by ground truth also
// needs the fused heading right at the goal: with the portable random generator seeds 1
// and 2 stop within 0.8° of the goal by the fused estimate but 6.6° and 4.7° off by
// ground truth, the fused yaw 7.0° and 3.9° in error after the final turn
// (docs/results/2026-12-04-portable-random.md). Before it, seed 1 alone failed (7.9°).
// So at least 2 of 4 must succeed by ground truth, a bar set by the localization.
TEST(ClosedLoopNavigationTest, ReachesTheGoalAroundATreeOnTheFusedEstimate) {
  const std::string yaml =
      "duration_s: 60\n"
      "scene:\n  name: one_tree\n  terrain: {extent_m: [-2, -4, 9, 4], default_material: grass}\n"
      "  objects:\n    - {type: tree, center: [3, 0.1], radius_m: 0.2, height_m: 4}\n"
      "    - {type: wall, from: [-1, 3], to: [8, 3], thickness_m: 0.25, height_m: 1.5, "
      "appearance: brick}\n"
      "    - {type: wall, from: [-1, -3], to: [8, -3], thickness_m: 0.25, height_m: 1.5, "
      "appearance: brick}\n"
      "robot:\n  stereo: {enabled: true}\n  range_sensor: {enabled: true}\n"
      "navigation:\n  enabled: true\n  mode: closed_loop\n  goal: {x_m: 6, y_m: 0, yaw_deg: 0}\n"
      "  stop_position_tolerance_m: 0.04\n  stop_heading_tolerance_deg: 1\n";
  int successes = 0;
  for (const char* seed : {"1", "2", "3", "4"}) {
    SCOPED_TRACE(std::string("seed ") + seed);
    const scenario::Scenario s = scenario::ParseScenario(yaml, "one_tree.yaml", {{"seed", seed}});
    const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) /
                                      (std::string("trackbed_closed_loop_nav_") + seed);
    const runner::RunMetrics m = runner::RunToFolder(s, dir);
    ASSERT_TRUE(m.navigation.has_value());
    EXPECT_EQ(m.navigation->status, "reached");
    std::printf("seed %s: final error %.3f m, %.2f deg\n", seed,
                m.navigation->final_position_error_m, m.navigation->final_heading_error_deg);
    successes += m.navigation->success;
    EXPECT_EQ(m.navigation->collisions, 0);
    EXPECT_GT(m.navigation->min_clearance_m, 0.2);
    EXPECT_GE(m.navigation->subgoals, 1);  // the tree was avoided by a sub-goal
    EXPECT_TRUE(std::filesystem::exists(dir / "navigation.csv"));
    EXPECT_TRUE(std::filesystem::exists(dir / "navigation.png"));
  }
  EXPECT_GE(successes, 2);
}

// The final turn on the tracked robot, on ground truth (so what shows is the controller
// against the vehicle, not the estimate): 1 m straight ahead on grass, then 90° in place
// to the goal's heading. Read from navigation.csv: the peak of the true heading past the
// goal's and the sign reversals of the commanded yaw rate once the heading is past 45°.
struct FinalTurn {
  double overshoot_deg = 0.0;
  int reversals = 0;
  runner::RunMetrics metrics;
};

FinalTurn RunFinalTurn(const std::string& time_constant_s) {
  const std::string yaml =
      "duration_s: 15\n"
      "scene:\n  name: final_turn\n  terrain: {extent_m: [-3, -3, 3, 3], default_material: grass}\n"
      "robot:\n  stereo: {enabled: false}\n  range_sensor: {enabled: true}\n"
      "outputs: {mcap: false}\n"
      "navigation:\n  enabled: true\n  mode: closed_loop\n  pose_source: ground_truth\n"
      "  goal: {x_m: 1, y_m: 0, yaw_deg: 90}\n"
      "  stop_position_tolerance_m: 0.04\n  stop_heading_tolerance_deg: 1\n"
      "  gauss_newton: {final_approach_radius_m: 0.2, final_time_constant_s: " +
      time_constant_s + "}\n";
  const scenario::Scenario s = scenario::ParseScenario(yaml, "final_turn.yaml");
  const std::filesystem::path dir =
      std::filesystem::path(testing::TempDir()) / ("trackbed_final_turn_" + time_constant_s);
  std::filesystem::remove_all(dir);
  FinalTurn turn;
  turn.metrics = runner::RunToFolder(s, dir);
  std::ifstream csv(dir / "navigation.csv");
  std::string line;
  std::getline(csv, line);  // header: t, x_m, y_m, yaw_rad, v_mps, yaw_rate_radps, ...
  double last_rate = 0.0;
  while (std::getline(csv, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    double t = 0.0, x = 0.0, y = 0.0, yaw = 0.0, v = 0.0, rate = 0.0;
    std::istringstream(line) >> t >> x >> y >> yaw >> v >> rate;
    turn.overshoot_deg = std::max(turn.overshoot_deg, yaw * 180.0 / M_PI - 90.0);
    if (yaw < M_PI / 4) continue;  // the reversals of the final turn's second half
    if (rate * last_rate < 0.0) ++turn.reversals;
    if (rate != 0.0) last_rate = rate;
  }
  return turn;
}

// The deadbeat final step, saturated at 0.5 rad/s, passes the goal's heading by over 2°
// and reverses (the chassis goes on turning for a tenth of a second after the command
// changes); with the final time constant (0.4 s, docs/navigation.md "Near the goal")
// the turn slows as it nears the goal's heading and settles within the success tolerance
// without a reversal.
TEST(ClosedLoopNavigationTest, TheFinalTimeConstantEndsTheTurnWithoutAReversal) {
  const FinalTurn deadbeat = RunFinalTurn("0");
  const FinalTurn spread = RunFinalTurn("0.4");
  std::printf("deadbeat: overshoot %.2f deg, %d reversal(s), final %.2f deg\n",
              deadbeat.overshoot_deg, deadbeat.reversals,
              deadbeat.metrics.navigation->final_heading_error_deg);
  std::printf("time constant 0.4 s: overshoot %.2f deg, %d reversal(s), final %.2f deg\n",
              spread.overshoot_deg, spread.reversals,
              spread.metrics.navigation->final_heading_error_deg);
  EXPECT_GT(deadbeat.overshoot_deg, 2.0);
  EXPECT_GE(deadbeat.reversals, 1);
  ASSERT_TRUE(spread.metrics.navigation.has_value());
  EXPECT_EQ(spread.metrics.navigation->status, "reached");
  EXPECT_TRUE(spread.metrics.navigation->success);
  EXPECT_LT(spread.metrics.navigation->final_heading_error_deg, 2.0);
  EXPECT_LT(spread.overshoot_deg, 1.0);
  EXPECT_EQ(spread.reversals, 0);
}

}  // namespace
}  // namespace trackbed
