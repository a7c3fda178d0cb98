// Skid-steer kinematics, the ICR expansion fit and the pure-pursuit driver:
// pure functions and a kinematic loop, no simulator.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "trackbed/common/skid_steer.h"
#include "trackbed/estimation/icr_calibration.h"
#include "trackbed/navigation/pure_pursuit.h"

namespace trackbed {
namespace {

TEST(SkidSteerTest, TwistAndTrackSpeedsAreInverse) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 100; ++k) {
    const kinematics::BodyTwist t{u(rng), u(rng)};
    const double gauge = 0.3 + std::abs(u(rng));
    const kinematics::BodyTwist back =
        kinematics::TwistFromTrackSpeeds(kinematics::TrackSpeedsFromTwist(t, gauge), gauge);
    EXPECT_NEAR(back.v_mps, t.v_mps, 1e-15);
    EXPECT_NEAR(back.yaw_rate_radps, t.yaw_rate_radps, 1e-14);
  }
}

TEST(SkidSteerTest, EncoderDistanceIsTheAbsoluteMeanTrackTravel) {
  EXPECT_DOUBLE_EQ(kinematics::EncoderDistanceIncrement(1.0, 3.0, 0.1), 0.2);
  EXPECT_DOUBLE_EQ(kinematics::EncoderDistanceIncrement(-1.0, -3.0, 0.1), 0.2);
  EXPECT_DOUBLE_EQ(kinematics::EncoderDistanceIncrement(-2.0, 2.0, 0.1), 0.0);  // turn in place
}

TEST(IcrCalibrationTest, RecoversTheExpansionFactorFromNoisySamples) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::uniform_real_distribution<double> rate(-1.0, 1.0);
  std::vector<estimation::IcrSample> samples;
  for (int k = 0; k < 5000; ++k) {
    const double truth = rate(rng);
    samples.push_back({1.37 * truth + noise(rng), truth});
  }
  const estimation::IcrFit fit = estimation::FitIcrExpansion(samples, 0.05);
  EXPECT_NEAR(fit.chi, 1.37, 0.005);
  EXPECT_NEAR(fit.rms_residual_radps, 0.02, 0.002);
  EXPECT_LT(fit.samples_used, 5000);  // near-zero rates are left out
  EXPECT_EQ(estimation::FitIcrExpansion({{0.01, 0.0}}).samples_used, 0);
  // The running fit (a run of hours): χ bit for bit, the residual to rounding.
  estimation::RunningIcrFit running(0.05);
  for (const estimation::IcrSample& s : samples) running.Add(s);
  const estimation::IcrFit r = running.Fit();
  EXPECT_EQ(r.chi, fit.chi);
  EXPECT_EQ(r.samples_used, fit.samples_used);
  EXPECT_NEAR(r.rms_residual_radps, fit.rms_residual_radps, 1e-12);
  EXPECT_EQ(estimation::RunningIcrFit().Fit().samples_used, 0);
}

// Drives a unicycle with the follower's commands.
navigation::Pose2 Follow(navigation::PurePursuit& follower, navigation::Pose2 pose,
                         double* max_cross_track, int* steps) {
  *max_cross_track = 0.0;
  const double dt = 0.05;
  for (*steps = 0; *steps < 20000; ++*steps) {
    const navigation::PurePursuitCommand c = follower.Update(pose);
    if (c.finished) break;
    if (c.progress_m > 1.0)
      *max_cross_track = std::max(*max_cross_track, std::abs(c.cross_track_m));
    pose.x += c.twist.v_mps * std::cos(pose.yaw) * dt;
    pose.y += c.twist.v_mps * std::sin(pose.yaw) * dt;
    pose.yaw += c.twist.yaw_rate_radps * dt;
  }
  return pose;
}

TEST(PurePursuitTest, FollowsAnLShapedPathToItsEnd) {
  navigation::PurePursuit follower({}, {{0, 0}, {10, 0}, {10, 6}}, false);
  EXPECT_DOUBLE_EQ(follower.length_m(), 16.0);
  double cross = 0.0;
  int steps = 0;
  const navigation::Pose2 end = Follow(follower, {0, 0, 0}, &cross, &steps);
  EXPECT_LT(std::hypot(end.x - 10, end.y - 6), 0.1);
  EXPECT_LT(cross, 0.5);  // cutting the corner with a 0.8 m look-ahead
  EXPECT_LT(steps, 20000);
}

TEST(PurePursuitTest, DrivesTheRequestedLapsOfAClosedLoop) {
  std::vector<Eigen::Vector2d> square = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  navigation::PurePursuit follower({}, square, true, 2);
  double cross = 0.0;
  int steps = 0;
  const navigation::Pose2 end = Follow(follower, {0, 0, 0}, &cross, &steps);
  // Two laps of 16 m at 0.4 m/s (corners cut): about 76 s; one lap would be half.
  EXPECT_GT(steps * 0.05, 65.0);
  EXPECT_LT(steps * 0.05, 90.0);
  EXPECT_LT(std::hypot(end.x, end.y), 0.5);
  EXPECT_LT(cross, 0.6);
}

TEST(PurePursuitTest, RejectsDegeneratePaths) {
  EXPECT_THROW(navigation::PurePursuit({}, {{1, 1}}, false), std::invalid_argument);
  EXPECT_THROW(navigation::PurePursuit({}, {{1, 1}, {1, 1}}, false), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed
