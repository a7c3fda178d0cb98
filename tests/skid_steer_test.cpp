// Skid steering and climbing against closed forms and published calibrations:
// the rigid-plastic ICR expansion of the station layout, Clearpath Jackal's
// calibrated multiplier, slip against grade, and stalls reported as such.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_scenarios.h"
#include "trackbed/estimation/icr_calibration.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/terrain_material.h"

namespace trackbed {
namespace {

using runner::RunClosedLoop;
using runner::RunMetrics;
using scenario::Scenario;
using testing::FlatTrackSpeedRun;

// Turning in place (left −0.2, right +0.2 m/s) on `material`, 10 s.
Scenario TurnInPlace(const std::string& material) {
  return FlatTrackSpeedRun(material, -0.2, 0.2, 10.0);
}

// Isotropic Coulomb friction (μ 0.8) with a shear modulus of 0.2 mm: the pads
// reach full shear within a fraction of a millimetre, the rigid-plastic limit.
sim::TerrainMaterial RigidPlasticGround() {
  sim::TerrainMaterial m;
  m.name = "rigid_plastic";
  m.friction_angle_deg = std::atan(0.8) * 180.0 / M_PI;
  m.shear_modulus_m = 0.0002;
  return m;
}

std::vector<double> EvenStations(double length, int n) {
  std::vector<double> xs;
  for (int i = 0; i < n; ++i) xs.push_back(-length / 2 + (i + 0.5) * length / n);
  return xs;
}

// The calibration run's turns in place, both ways (its first 20 s).
Scenario CalibrationTurnsInPlace() {
  return scenario::LoadScenario(
      std::string(TRACKBED_SOURCE_DIR) + "/scenes/calibration/icr_turns.yaml",
      {{"duration_s", "20"}});
}

TEST(SkidSteerTest, RigidPlasticTurnInPlaceMatchesTheMomentBalance) {
  // Today's six road wheels, and two stations a side (closed form 1 + (a/c)²).
  for (const std::vector<double>& xs : {EvenStations(0.55, 6), std::vector<double>{-0.2, 0.2}}) {
    Scenario s = CalibrationTurnsInPlace();
    s.scene.terrain.default_material = "rigid_plastic";
    s.scene.terrain.materials = {RigidPlasticGround()};
    s.robot.vehicle.station_x_m = xs;
    const RunMetrics m = RunClosedLoop(s);
    ASSERT_TRUE(m.completed) << m.stop_reason;
    ASSERT_GT(m.icr.samples_used, 1900);  // both directions
    const double c = s.robot.vehicle.track_gauge_m / 2;
    const double expected = estimation::RigidPlasticIcrExpansion(xs, c);
    EXPECT_NEAR(m.icr.chi / expected, 1.0, 0.02)
        << xs.size() << " stations: χ " << m.icr.chi << " against " << expected;
  }
  EXPECT_NEAR(estimation::RigidPlasticIcrExpansion({-0.2, 0.2}, 0.25), 1.0 + 0.64, 1e-12);
}

TEST(SkidSteerTest, JackalOnTheHardFloorMatchesItsCalibratedMultiplier) {
  // Clearpath Jackal's geometry (scenes/calibration/icr_turns_jackal.yaml, from its
  // URDF); its control.yaml calibrates wheel_separation_multiplier 1.5. The turns
  // in place, both ways.
  const RunMetrics m = RunClosedLoop(scenario::LoadScenario(
      std::string(TRACKBED_SOURCE_DIR) + "/scenes/calibration/icr_turns_jackal.yaml",
      {{"duration_s", "20"}}));
  ASSERT_TRUE(m.completed) << m.stop_reason;
  ASSERT_GT(m.icr.samples_used, 1900);
  EXPECT_NEAR(m.icr.chi / 1.5, 1.0, 0.07) << "χ " << m.icr.chi;
  // And its rigid-plastic value: wheels at ±0.131 m, half track 0.1878 m.
  EXPECT_NEAR(m.icr.chi / estimation::RigidPlasticIcrExpansion({-0.131, 0.131}, 0.37559 / 2), 1.0,
              0.02);
}

// Mean slip ratio of both tracks, 6–14 s into a straight climb at 0.4 m/s.
double SteadyClimbSlip(double slope_deg) {
  Scenario s = FlatTrackSpeedRun("dry_sand", 0.4, 0.4, 14.0);
  s.scene.terrain.extent_m = {-2, -3, 8, 3};
  s.scene.terrain.roughness.slope_x = std::tan(slope_deg * M_PI / 180.0);
  double sum = 0.0;
  int n = 0;
  runner::RunObservers obs;
  obs.on_sample = [&](const runner::RunSample& r) {
    if (r.t_s < 6.0) return;
    for (const robot::TrackState& t : r.tracks) {
      sum += (t.track_speed_mps - t.ground_speed_mps) / t.track_speed_mps;
      ++n;
    }
  };
  const RunMetrics m = RunClosedLoop(s, obs);
  EXPECT_TRUE(m.completed) << m.stop_reason;
  return sum / n;
}

TEST(SkidSteerTest, SlipRisesWithGradeAndIsConvexInTheGradeForce) {
  const std::vector<double> angles = {0.0, 5.0, 10.0, 15.0};
  std::vector<double> slip, force;
  for (double a : angles) {
    slip.push_back(SteadyClimbSlip(a));
    force.push_back(std::sin(a * M_PI / 180.0));  // grade force over weight
  }
  for (std::size_t k = 1; k < slip.size(); ++k) {
    EXPECT_GT(slip[k], slip[k - 1]) << angles[k] << " deg";
    if (k + 1 < slip.size()) {
      const double before = (slip[k] - slip[k - 1]) / (force[k] - force[k - 1]);
      const double after = (slip[k + 1] - slip[k]) / (force[k + 1] - force[k]);
      EXPECT_GT(after, before) << "slip against grade force not convex at " << angles[k] << " deg";
    }
  }
}

TEST(SkidSteerTest, TurningInPlaceCompletesOrReportsAStallOnEveryMaterial) {
  // Never silent non-motion: a run either says it stalled or the robot turned.
  int completed = 0;
  for (const sim::TerrainMaterial& material : sim::BuiltinMaterials()) {
    SCOPED_TRACE(material.name);
    double yaw_rad = 0.0;
    runner::RunObservers obs;
    obs.on_sample = [&](const runner::RunSample& r) {
      yaw_rad += std::abs(r.chassis.omega_world.z()) * 0.01;  // encoder rate, 100 Hz
    };
    const RunMetrics m = RunClosedLoop(TurnInPlace(material.name), obs);
    ASSERT_TRUE(m.completed) << m.stop_reason;
    if (m.stop_reason == "stalled") continue;
    EXPECT_EQ(m.stop_reason, "duration reached");
    // 10 s at ±0.2 m/s: 8 rad of track-implied yaw, less χ's share.
    EXPECT_GT(yaw_rad, 4.0);
    ++completed;
  }
  EXPECT_GE(completed, 1);
}

TEST(SkidSteerTest, AMotorTooWeakToSkidStallsAndTheRunSaysSo) {
  Scenario s = TurnInPlace("hard_floor");
  s.robot.vehicle.motor.max_torque_nm = 2.0;  // a tenth of the shipped drive
  const RunMetrics m = RunClosedLoop(s);
  EXPECT_TRUE(m.completed);
  EXPECT_EQ(m.stop_reason, "stalled");
  EXPECT_LT(m.sim_time_s, 3.0);
}

}  // namespace
}  // namespace trackbed
