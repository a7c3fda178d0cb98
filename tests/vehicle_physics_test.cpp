// The tracked vehicle on terrain: slip emerges from terramechanics and depends
// on the ground; encoders see the sprockets. Thresholds are on ground truth.
#include <cmath>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "test_scenarios.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed {
namespace {

using runner::RunClosedLoop;
using runner::RunMetrics;
using testing::FlatTrackSpeedRun;

double MeanAbsSlipRatio(const RunMetrics& m) {
  return (m.slip[0].sum_abs_ratio + m.slip[1].sum_abs_ratio) /
         static_cast<double>(m.slip[0].samples + m.slip[1].samples);
}

double EncoderDistanceError(const RunMetrics& m) {
  return (m.encoder_distance_m - m.distance_m) / m.distance_m;
}

TEST(VehiclePhysicsTest, StraightTenMetresOnHardFloorMatchesTheEncoders) {
  const RunMetrics m = RunClosedLoop(FlatTrackSpeedRun("hard_floor", 0.4, 0.4, 25.0));
  ASSERT_TRUE(m.completed) << m.stop_reason;
  EXPECT_NEAR(m.distance_m, 10.0, 0.2);
  EXPECT_LT(std::abs(EncoderDistanceError(m)), 0.01);
  EXPECT_LT(MeanAbsSlipRatio(m), 0.02);
}

TEST(VehiclePhysicsTest, LooseSoilSlipsMoreAndEncodersOverEstimateDistance) {
  const RunMetrics floor = RunClosedLoop(FlatTrackSpeedRun("hard_floor", 0.4, 0.4, 25.0));
  for (const char* soil : {"lete_sand", "dry_sand", "sandy_loam", "clay", "grass"}) {
    const RunMetrics m = RunClosedLoop(FlatTrackSpeedRun(soil, 0.4, 0.4, 25.0));
    ASSERT_TRUE(m.completed) << soil << ": " << m.stop_reason;
    EXPECT_GT(MeanAbsSlipRatio(m), MeanAbsSlipRatio(floor)) << soil;
    EXPECT_GT(m.encoder_distance_m, m.distance_m) << soil;
    EXPECT_GT(EncoderDistanceError(m), EncoderDistanceError(floor)) << soil;
  }
}

TEST(VehiclePhysicsTest, SkidSteerTurnsExpandTheIcrAndTheExpansionDependsOnTerrain) {
  std::map<std::string, double> chi_turn_in_place, chi_curve;
  for (const char* ground : {"hard_floor", "dry_sand", "grass"}) {
    const RunMetrics spin = RunClosedLoop(FlatTrackSpeedRun(ground, -0.2, 0.2, 15.0));
    const RunMetrics curve = RunClosedLoop(FlatTrackSpeedRun(ground, 0.3, 0.5, 15.0));
    ASSERT_TRUE(spin.completed && curve.completed) << ground;
    ASSERT_GT(spin.icr.samples_used, 1000);
    ASSERT_GT(curve.icr.samples_used, 1000);
    // Encoders imply more yaw than the robot makes: χ = B_eff / B > 1.
    EXPECT_GT(spin.icr.chi, 1.1) << ground;
    EXPECT_GT(curve.icr.chi, 1.1) << ground;
    chi_turn_in_place[ground] = spin.icr.chi;
    chi_curve[ground] = curve.icr.chi;
  }
  // Softer ground with a larger shear modulus expands the ICRs further in a curve.
  EXPECT_GT(chi_curve["dry_sand"], chi_curve["hard_floor"] + 0.005);
  EXPECT_GT(chi_curve["grass"], chi_curve["hard_floor"] + 0.005);
}

TEST(VehiclePhysicsTest, TurnRateDoesNotDependOnTheStartingHeading) {
  // Bullet's own friction is anisotropic (bullet3 #2590); the track model must not be.
  for (const auto& [left, right] : {std::pair{-0.2, 0.2}, std::pair{0.3, 0.5}}) {
    std::vector<double> rates;
    for (double yaw_deg : {0.0, 30.0, 45.0}) {
      double yaw_sum = 0.0;
      int n = 0;
      runner::RunObservers obs;
      obs.on_sample = [&](const runner::RunSample& s) {
        if (s.t_s > 2.0 && s.t_s < 10.0) {
          yaw_sum += s.chassis.omega_world.z();
          ++n;
        }
      };
      RunClosedLoop(FlatTrackSpeedRun("hard_floor", left, right, 10.0, yaw_deg), obs);
      rates.push_back(yaw_sum / n);
    }
    for (double r : rates) EXPECT_NEAR(r / rates[0], 1.0, 0.02) << left << " " << right;
  }
}

TEST(VehiclePhysicsTest, UnevenSoilMakesSeedsDifferOnlyWhenItIsOn) {
  // A curve on grass: with uniform soil the physics does not depend on the seed;
  // with soil variation each seed is its own field.
  auto run = [](std::uint64_t seed, double amplitude) {
    scenario::Scenario s = FlatTrackSpeedRun("grass", 0.3, 0.5, 10.0);
    s.seed = seed;
    s.scene.terrain.soil_variation.amplitude = amplitude;
    s.scene.terrain.soil_variation.correlation_length_m = 1.0;
    const RunMetrics m = RunClosedLoop(s);
    EXPECT_TRUE(m.completed) << m.stop_reason;
    return m;
  };
  EXPECT_EQ(run(1, 0.0).icr.chi, run(2, 0.0).icr.chi);
  const double a = run(1, 0.4).icr.chi, b = run(2, 0.4).icr.chi;
  EXPECT_NE(a, b);
  EXPECT_EQ(a, run(1, 0.4).icr.chi);  // and each seed reproduces itself
}

TEST(VehiclePhysicsTest, TenMinutesOnTheOutdoorSceneStayFiniteAndAboveGround) {
  const scenario::Scenario s = scenario::LoadScenario(
      std::string(TRACKBED_SOURCE_DIR) + "/scenes/outdoor.yaml",
      {{"duration_s", "600"}, {"drive.laps", "10"}, {"robot.stereo.enabled", "false"}});
  double max_speed = 0.0, max_tilt = 0.0, min_clearance = 1e9;
  bool finite = true;
  runner::RunObservers obs;
  obs.on_sample = [&](const runner::RunSample& r) {
    finite = finite && r.chassis.T_world_body.matrix().allFinite() &&
             r.chassis.v_world.allFinite() && r.chassis.omega_world.allFinite();
    max_speed = std::max(max_speed, r.chassis.v_world.norm());
    max_tilt = std::max(max_tilt, std::acos(r.chassis.T_world_body.linear()(2, 2)));
  };
  const RunMetrics m = RunClosedLoop(s, obs);
  min_clearance = m.min_com_height_m;
  ASSERT_TRUE(m.completed) << m.stop_reason;
  EXPECT_EQ(m.stop_reason, "duration reached");
  EXPECT_NEAR(m.sim_time_s, 600.0, 1e-6);
  EXPECT_TRUE(finite);
  EXPECT_LT(max_speed, 1.0);               // commanded 0.4 m/s: nothing flies off
  EXPECT_LT(max_tilt, 25.0 * M_PI / 180);  // undulating ground, no roll-over
  // The centre of mass stays well above the ground (0.20 m at rest).
  EXPECT_GT(min_clearance, 0.12);
  EXPECT_GT(m.distance_m, 200.0);
}

}  // namespace
}  // namespace trackbed
