// The carrier of a pose path (robot/pose_path_carrier.h): it goes where the curve
// through the waypoints goes, at the set speed, resting on the ground, and its virtual
// tracks count what it drove.
#include "trackbed/robot/pose_path_carrier.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace trackbed::robot {
namespace {

calibration::VehicleCalibration Tracks(double radius_m, double gauge_m) {
  calibration::VehicleCalibration c;
  c.sprocket_radius_left_m = c.sprocket_radius_right_m = radius_m;
  c.track_gauge_m = gauge_m;
  return c;
}

sim::TerrainOptions Flat(double half_extent_m) {
  sim::TerrainOptions t;
  t.extent_m = {-half_extent_m, -half_extent_m, half_extent_m, half_extent_m};
  t.cell_size_m = 0.5;
  return t;
}

// Drives the carrier for t_s in steps of dt_s.
void Drive(PosePathCarrier* carrier, double t_s, double dt_s = 0.001) {
  const auto steps = static_cast<int>(std::lround(t_s / dt_s));
  for (int k = 0; k < steps; ++k) carrier->ApplyForces(dt_s);
}

TEST(PosePathCarrierTest, AStraightPathIsDrivenAtTheSetSpeedAndCountedByBothTracks) {
  const sim::Terrain terrain(Flat(60), 1);
  PosePathOptions o;
  o.waypoints = {{-40, 2}, {0, 2}, {40, 2}};
  o.speed_mps = 12.5;
  o.body_height_m = 0.6;
  const PosePathCarrier carrier_at_rest(o, &terrain, Tracks(0.3, 1.6), 9.81);
  EXPECT_NEAR(carrier_at_rest.length_m(), 80.0, 1e-9);
  EXPECT_NEAR(carrier_at_rest.end_time_s(), 6.4, 1e-9);

  PosePathCarrier carrier(o, &terrain, Tracks(0.3, 1.6), 9.81);
  Drive(&carrier, 2.0);
  const ChassisState s = carrier.chassis();
  EXPECT_NEAR(s.T_world_body.translation().x(), -40.0 + 25.0, 1e-6);
  EXPECT_NEAR(s.T_world_body.translation().y(), 2.0, 1e-9);
  EXPECT_NEAR(s.T_world_body.translation().z(), 0.6, 1e-9);
  EXPECT_NEAR((s.v_world - Eigen::Vector3d(12.5, 0, 0)).norm(), 0.0, 1e-6);
  EXPECT_NEAR(s.omega_world.norm(), 0.0, 1e-9);
  for (const Side side : {kLeft, kRight}) {
    EXPECT_NEAR(carrier.track(side).sprocket_angle_rad * 0.3, 25.0, 1e-6);
    EXPECT_EQ(carrier.track(side).slip_velocity_mps, 0.0);
  }
}

TEST(PosePathCarrierTest, ACircleIsFollowedWithItsTangentHeadingAndYawRate) {
  const sim::Terrain terrain(Flat(60), 1);
  PosePathOptions o;
  const double radius = 20.0;
  for (int k = 0; k < 72; ++k) {
    const double a = 2.0 * M_PI * k / 72;
    o.waypoints.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  o.closed = true;
  o.laps = 2;
  o.speed_mps = 8.0;
  PosePathCarrier carrier(o, &terrain, Tracks(0.3, 1.6), 9.81);
  // Twice round, within the curve's departure from the circle between waypoints.
  EXPECT_NEAR(carrier.length_m(), 2 * 2 * M_PI * radius, 0.05);
  for (int check = 0; check < 8; ++check) {
    Drive(&carrier, 1.3);
    const ChassisState s = carrier.chassis();
    const Eigen::Vector3d p = s.T_world_body.translation();
    EXPECT_NEAR(p.head<2>().norm(), radius, 0.02);
    // Heading along the tangent (counter-clockwise), speed and yaw rate v / R.
    const Eigen::Vector3d tangent = Eigen::Vector3d(-p.y(), p.x(), 0).normalized();
    EXPECT_NEAR(s.T_world_body.linear().col(0).dot(tangent), 1.0, 1e-4);
    EXPECT_NEAR(s.v_world.norm(), 8.0, 0.01);
    EXPECT_NEAR(s.omega_world.z(), 8.0 / radius, 0.01 * 8.0 / radius);
  }
  // Skid-steer kinematics without slip: the outer (right) track runs faster.
  EXPECT_NEAR(carrier.track(kRight).track_speed_mps - carrier.track(kLeft).track_speed_mps,
              1.6 * 8.0 / radius, 0.01);
}

TEST(PosePathCarrierTest, TheBodyRestsOnASlopeAndStopsAtThePathsEnd) {
  sim::TerrainOptions t = Flat(60);
  t.roughness.slope_x = 0.1;
  const sim::Terrain terrain(t, 1);
  PosePathOptions o;
  o.waypoints = {{0, 0}, {30, 0}};
  o.speed_mps = 10.0;
  o.body_height_m = 0.5;
  PosePathCarrier carrier(o, &terrain, Tracks(0.3, 1.6), 9.81);
  Drive(&carrier, 1.0);
  ChassisState s = carrier.chassis();
  const Eigen::Matrix3d R = s.T_world_body.linear();
  EXPECT_NEAR(std::atan2(R(2, 0), R(0, 0)), std::atan(0.1), 1e-6);  // pitched up the slope
  const Eigen::Vector3d normal = Eigen::Vector3d(-0.1, 0, 1).normalized();
  const Eigen::Vector3d ground(10.0, 0.0, terrain.Height(10.0, 0.0));
  EXPECT_NEAR((s.T_world_body.translation() - (ground + 0.5 * normal)).norm(), 0.0, 1e-6);
  EXPECT_NEAR(s.v_world.z(), 10.0 * 0.1, 1e-6);  // climbing at the slope times the speed
  Drive(&carrier, 3.0);                          // past the end at 3 s
  s = carrier.chassis();
  const Eigen::Vector3d end(30.0, 0.0, terrain.Height(30.0, 0.0));
  EXPECT_NEAR((s.T_world_body.translation() - (end + 0.5 * normal)).norm(), 0.0, 1e-6);
  EXPECT_EQ(s.v_world.norm(), 0.0);
  EXPECT_EQ(carrier.track(kLeft).sprocket_speed_radps, 0.0);
}

TEST(PosePathCarrierTest, APathThatCannotBeACurveIsRefused) {
  const sim::Terrain terrain(Flat(10), 1);
  PosePathOptions o;
  o.waypoints = {{0, 0}};
  EXPECT_THROW(PosePathCarrier(o, &terrain, Tracks(0.1, 0.5), 9.81), std::invalid_argument);
  o.waypoints = {{0, 0}, {1, 0}, {1, 0}};
  EXPECT_THROW(PosePathCarrier(o, &terrain, Tracks(0.1, 0.5), 9.81), std::invalid_argument);
  o.waypoints = {{0, 0}, {1, 0}};
  o.speed_mps = 0.0;
  EXPECT_THROW(PosePathCarrier(o, &terrain, Tracks(0.1, 0.5), 9.81), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::robot
