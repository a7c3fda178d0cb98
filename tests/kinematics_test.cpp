// Skid-steer kinematics, the ICR expansion fit and the pure-pursuit driver:
// pure functions and a kinematic loop, no simulator.
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

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

// A constructed calibration run at 100 Hz: the true yaw rate held for 2 s (200
// samples) at a time, each hold at a rate drawn from ±[min_rate, max_rate]; the
// encoders see χ times it plus white noise σ_enc, the reference sees it plus white
// noise σ_ref (yaw the terrain causes and the tracks did not command).
std::vector<estimation::IcrSample> ConstructedRun(double chi, double min_rate, double max_rate,
                                                  double sigma_enc, double sigma_ref,
                                                  std::uint64_t seed, int holds = 40) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> rate(min_rate, max_rate);
  std::bernoulli_distribution left(0.5);
  std::normal_distribution<double> enc_noise(0.0, sigma_enc), ref_noise(0.0, sigma_ref);
  std::vector<estimation::IcrSample> samples;
  for (int h = 0; h < holds; ++h) {
    const double truth = (left(rng) ? 1.0 : -1.0) * rate(rng);
    for (int k = 0; k < 200; ++k)
      samples.push_back({chi * truth + enc_noise(rng), truth + ref_noise(rng)});
  }
  return samples;
}

// The least-squares slope through the origin on the reference, per sample.
double ReferenceLeastSquares(const std::vector<estimation::IcrSample>& samples) {
  double sxy = 0.0, sxx = 0.0;
  for (const estimation::IcrSample& s : samples) {
    if (std::abs(s.reference_yaw_rate_radps) < 0.05) continue;
    sxy += s.reference_yaw_rate_radps * s.encoder_yaw_rate_radps;
    sxx += s.reference_yaw_rate_radps * s.reference_yaw_rate_radps;
  }
  return sxy / sxx;
}

TEST(IcrCalibrationTest, RecoversTheExpansionFactorWithNoiseInBothRates) {
  // Turning like the calibration run (0.2–0.8 rad/s); σ 0.02 rad/s on the encoders,
  // 0.2 rad/s on the reference: least squares on the reference loses 1/(1 + σ²/E[x²])
  // ≈ 13 % of χ, the fit on 1 s windows none of it.
  for (std::uint64_t seed : {1, 2, 3}) {
    const auto samples = ConstructedRun(1.37, 0.2, 0.8, 0.02, 0.2, seed);
    const estimation::IcrFit fit = estimation::FitIcrExpansion(samples);
    EXPECT_LT(ReferenceLeastSquares(samples), 1.25) << "seed " << seed;
    EXPECT_NEAR(fit.chi, 1.37, 0.015) << "seed " << seed;
    EXPECT_NEAR(fit.chi, 1.37, 3.0 * fit.chi_stderr) << "seed " << seed;
    EXPECT_GT(fit.chi_stderr, 0.0);
    EXPECT_LT(fit.chi_stderr, 0.01);
    EXPECT_TRUE(fit.identified) << fit.reason;
    EXPECT_EQ(fit.reason, "");
    EXPECT_EQ(fit.windows_used, 80);
    EXPECT_EQ(fit.samples_used, 8000);
    // Residuals: both noises over a window of 100 samples, the reference's times χ.
    EXPECT_NEAR(fit.rms_residual_radps, std::hypot(0.002, 1.37 * 0.02), 0.006);
  }
}

TEST(IcrCalibrationTest, TheStandardErrorCoversTheSpreadOverSeeds) {
  // 30 constructed runs: the jackknife's standard error against the spread of χ.
  double sum = 0.0, sum_sq = 0.0, stderr_sum = 0.0;
  const int runs = 30;
  for (int seed = 0; seed < runs; ++seed) {
    const estimation::IcrFit fit =
        estimation::FitIcrExpansion(ConstructedRun(1.25, 0.2, 0.8, 0.02, 0.2, 100 + seed));
    sum += fit.chi;
    sum_sq += fit.chi * fit.chi;
    stderr_sum += fit.chi_stderr;
  }
  const double mean = sum / runs;
  const double spread = std::sqrt((sum_sq - runs * mean * mean) / (runs - 1));
  EXPECT_NEAR(mean, 1.25, 0.002);
  EXPECT_GT(stderr_sum / runs, 0.6 * spread);
  EXPECT_LT(stderr_sum / runs, 1.6 * spread);
}

TEST(IcrCalibrationTest, SteeringFasterThanTheBodyFollowsAveragesOut) {
  // A repeater's steering: ±0.3 rad/s switched every 0.1 s on top of turns of ±0.4 rad/s
  // held 10 s; the body follows the switching through a first-order lag of 0.3 s, so
  // its yaw rate barely sees it. Sample by sample the encoders' rate is not χ times
  // the true one; over 1 s windows (five periods) it is.
  const double chi = 1.25, dt = 0.01, tau = 0.3;
  std::vector<estimation::IcrSample> samples;
  double followed = 0.0;
  for (int k = 0; k < 6000; ++k) {
    const double turn = (k / 1000) % 2 == 0 ? 0.4 : -0.4;
    const double switching = (k / 10) % 2 == 0 ? 0.3 : -0.3;
    followed += (switching - followed) * dt / tau;
    samples.push_back({chi * (turn + switching), turn + followed});
  }
  const estimation::IcrFit fit = estimation::FitIcrExpansion(samples);
  EXPECT_NEAR(fit.chi, chi, 0.01);
  EXPECT_TRUE(fit.identified) << fit.reason;
  EXPECT_GT(estimation::FitIcrExpansion(samples, 1).chi, chi + 0.2);  // sample by sample
}

TEST(IcrCalibrationTest, GentleTurningIsNotIdentified) {
  // A path follower's turns: 0.05–0.15 rad/s, noise in the reference as on rough ground.
  const estimation::IcrFit fit =
      estimation::FitIcrExpansion(ConstructedRun(1.25, 0.05, 0.15, 0.02, 0.1, 4));
  EXPECT_FALSE(fit.identified);
  EXPECT_LT(fit.turn_rms_radps, estimation::IcrIdentification::kMinTurnRmsRadps);
  EXPECT_EQ(fit.reason.rfind("turning too gentle: RMS encoder yaw rate 0.1", 0), 0u) << fit.reason;
}

TEST(IcrCalibrationTest, ANoisyFitIsNotIdentified) {
  // Enough turning, but a reference so noisy (3 rad/s per sample, 0.3 rad/s over a
  // window) over 12 windows that the standard error exceeds the bound.
  const estimation::IcrFit fit =
      estimation::FitIcrExpansion(ConstructedRun(1.25, 0.2, 0.8, 0.02, 3.0, 5, 6));
  EXPECT_EQ(fit.windows_used, 12);
  EXPECT_FALSE(fit.identified);
  EXPECT_GT(fit.chi_stderr, estimation::IcrIdentification::kMaxStderr);
  EXPECT_EQ(fit.reason.rfind("standard error 0.", 0), 0u) << fit.reason;
}

TEST(IcrCalibrationTest, NoTurningLeavesChiAtOneWithTheReason) {
  const estimation::IcrFit none = estimation::FitIcrExpansion({{0.01, 0.0}, {0.0, 0.3}}, 1);
  EXPECT_EQ(none.windows_used, 0);
  EXPECT_EQ(none.samples_used, 0);
  EXPECT_EQ(none.chi, 1.0);
  EXPECT_TRUE(std::isnan(none.chi_stderr));
  EXPECT_FALSE(none.identified);
  EXPECT_EQ(none.reason, "too little turning: 0 window(s) above 0.05 rad/s (fewer than 10)");
  // 950 samples: nine whole windows, the rest left over.
  const estimation::IcrFit few =
      estimation::FitIcrExpansion(std::vector<estimation::IcrSample>(950, {0.5, 0.4}));
  EXPECT_EQ(few.windows_used, 9);
  EXPECT_EQ(few.samples_used, 900);
  EXPECT_DOUBLE_EQ(few.chi, 1.25);
  EXPECT_EQ(few.reason, "too little turning: 9 window(s) above 0.05 rad/s (fewer than 10)");
  EXPECT_THROW(estimation::FitIcrExpansion({}, 0), std::invalid_argument);
}

TEST(IcrCalibrationTest, ALongRunKeepsAtMostFortyGroups) {
  // 100 000 windows of one sample: the fit holds 20–40 groups, and its χ is the one of
  // the sums.
  estimation::RunningIcrFit running(1, 0.05);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> rate(0.2, 0.8);
  double yy = 0.0, yx = 0.0;
  for (int k = 0; k < 100000; ++k) {
    const double x = rate(rng), y = 1.3 * x + 0.01 * ((k % 7) - 3);
    running.Add({y, x});
    yy += y * y;
    yx += y * x;
    EXPECT_LE(running.groups(), 40u);
  }
  EXPECT_GE(running.groups(), 20u);
  const estimation::IcrFit fit = running.Fit();
  EXPECT_EQ(fit.windows_used, 100000);
  EXPECT_EQ(fit.chi, yy / yx);
  EXPECT_GT(fit.chi_stderr, 0.0);
  EXPECT_LT(fit.chi_stderr, 1e-3);
  EXPECT_TRUE(fit.identified) << fit.reason;
  EXPECT_THROW(estimation::RunningIcrFit(0), std::invalid_argument);
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
