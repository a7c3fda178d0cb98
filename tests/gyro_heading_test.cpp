// The gyro as a rotation source (estimation/gyro_bias.h, estimation/covariance_fusion.h):
// the bias from zero-velocity intervals on synthetic IMU streams with a known bias, the
// gyro-led wheel odometry's heading through the localization stack, and the covariance
// fusion's combination and gate.
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "trackbed/common/pose2.h"
#include "trackbed/common/random.h"
#include "trackbed/estimation/covariance_fusion.h"
#include "trackbed/estimation/gyro_bias.h"
#include "trackbed/estimation/localization.h"
#include "trackbed/estimation/wheel_odometry.h"

namespace trackbed::estimation {
namespace {

const Eigen::Vector3d kBias(1.0e-3, -2.0e-3, 2.5e-3);  // rad/s, 1–2.5 turn-on σ

// A gyro of the `typical` part's white noise (ADIS16470, 0.008 °/s/√Hz).
GyroModel TypicalGyro() {
  GyroModel m;
  m.noise_density = 0.008 * M_PI / 180.0;
  m.bias_random_walk = 0.0;
  m.turn_on_bias_std = 1e-3;
  return m;
}

// Feeds `seconds` of a robot standing still (encoders at 100 Hz with fixed counts, the
// gyro at 200 Hz reading the bias plus white noise of density `noise`), from t0.
void FeedStandstill(ZeroVelocityGyroBias* zupt, double t0, double seconds, double noise,
                    random::Generator* rng) {
  const double dt = 0.005, per_sample = noise / std::sqrt(dt);
  const int n = static_cast<int>(std::lround(seconds / dt));
  for (int k = 1; k <= n; ++k) {
    const double t = t0 + k * dt;
    const Eigen::Vector3d white(rng->Gaussian(), rng->Gaussian(), rng->Gaussian());
    zupt->AddGyroSample(t, kBias + per_sample * white);
    if (k % 2 == 0) zupt->AddEncoderSample(t, 1000, 2000);
  }
}

TEST(ZeroVelocityGyroBiasTest, WithoutNoiseTheStandstillGivesTheBiasExactly) {
  GyroModel model = TypicalGyro();
  model.noise_density = 0.0;
  ZeroVelocityGyroBias zupt(model, 0.5);
  random::Generator rng(1);
  FeedStandstill(&zupt, 0.0, 2.0, 0.0, &rng);
  EXPECT_TRUE(zupt.standstill());
  EXPECT_NEAR(zupt.standstill_s(), 1.5, 0.011);  // counted once the window has passed
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(zupt.bias()(i), kBias(i), 1e-15);
}

TEST(ZeroVelocityGyroBiasTest, TenSecondsOfStandstillBoundTheErrorByTheNoiseDensity) {
  const GyroModel model = TypicalGyro();
  ZeroVelocityGyroBias zupt(model, 0.5);
  random::Generator rng(7);
  FeedStandstill(&zupt, 0.0, 10.0, model.noise_density, &rng);
  // 9.5 s of samples: σ = N/√T = 4.5e-5 rad/s per axis; the filter's own variance says so.
  const double sigma = model.noise_density / std::sqrt(9.5);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(zupt.bias()(i), kBias(i), 4.0 * sigma) << "axis " << i;
    EXPECT_NEAR(std::sqrt(zupt.variance()(i)), sigma, 0.02 * sigma) << "axis " << i;
  }
  // The bias is 22–55 σ from zero: the estimate did learn it.
  EXPECT_GT(std::abs(zupt.bias().z()), 10.0 * sigma);
}

TEST(ZeroVelocityGyroBiasTest, SamplesWhileTheEncodersMoveLeaveTheEstimate) {
  GyroModel model = TypicalGyro();
  model.noise_density = 0.0;
  ZeroVelocityGyroBias zupt(model, 0.5);
  random::Generator rng(1);
  FeedStandstill(&zupt, 0.0, 2.0, 0.0, &rng);
  // Driving: the counts change at every encoder sample and the gyro reads a turn from
  // its first sample on, before the encoders have said so.
  for (int k = 1; k <= 400; ++k) {
    const double t = 2.0 + 0.005 * k;
    zupt.AddGyroSample(t, kBias + Eigen::Vector3d(0.0, 0.0, 0.5));
    if (k % 2 == 0) {
      zupt.AddEncoderSample(t, 1000 + k, 2000 + 2 * k);
      EXPECT_FALSE(zupt.standstill());
    }
  }
  EXPECT_NEAR(zupt.bias().z(), kBias.z(), 1e-15);
  // Stopped again: only once the window has passed do samples count.
  zupt.AddEncoderSample(4.01, 1400, 2800);
  zupt.AddEncoderSample(4.3, 1400, 2800);
  EXPECT_FALSE(zupt.standstill());
  zupt.AddEncoderSample(4.51, 1400, 2800);
  EXPECT_TRUE(zupt.standstill());
}

TEST(ZeroVelocityGyroBiasTest, ACountTogglingByATickIsStillAStandstill) {
  GyroModel model = TypicalGyro();
  model.noise_density = 0.0;
  ZeroVelocityGyroBias zupt(model, 0.5);
  // The chassis rocks on its suspension: both counts toggle between -1 and 0.
  for (int k = 1; k <= 400; ++k) {
    const double t = 0.005 * k;
    zupt.AddGyroSample(t, kBias);
    if (k % 2 == 0) zupt.AddEncoderSample(t, -(k / 2 % 2), -(k / 2 % 2));
  }
  EXPECT_TRUE(zupt.standstill());
  EXPECT_NEAR(zupt.bias().z(), kBias.z(), 1e-15);
  // Two ticks on: motion.
  zupt.AddEncoderSample(2.01, 2, 0);
  EXPECT_FALSE(zupt.standstill());
}

TEST(ZeroVelocityGyroBiasTest, TheChassisSettlingIsNotTakenForTheBias) {
  GyroModel model = TypicalGyro();
  ZeroVelocityGyroBias zupt(model, 0.5);
  random::Generator rng(5);
  // 10 s still, with a 0.05 rad/s rock about z from 1 s to 1.2 s the encoders miss.
  const double per_sample = model.noise_density / std::sqrt(0.005);
  for (int k = 1; k <= 2000; ++k) {
    const double t = 0.005 * k;
    const double rock = t > 1.0 && t <= 1.2 ? 0.05 : 0.0;
    zupt.AddGyroSample(t, kBias + Eigen::Vector3d(0.0, 0.0, rock) +
                              per_sample * rng.Gaussian() * Eigen::Vector3d::UnitZ());
    if (k % 2 == 0) zupt.AddEncoderSample(t, 0, 0);
  }
  // 0.2 s of 0.05 rad/s over 9.5 s would be 1.05e-3 rad/s off; left out, within 4 σ.
  EXPECT_NEAR(zupt.bias().z(), kBias.z(), 4.0 * model.noise_density / std::sqrt(9.3));
}

TEST(GyroModelTest, RotationVarianceAddsBiasAndWhiteNoise) {
  GyroModel m;
  m.noise_density = 2e-4;
  m.bias_instability_std = 3e-4;
  EXPECT_DOUBLE_EQ(m.RotationVariance(0.1, 4e-8),
                   (4e-8 + 9e-8) * 0.01 + 4e-8 * 0.1);  // (σ_b·dt)² + N²·dt
}

// Ticks of a 0.1 m sprocket with 4096 counts a revolution for a distance [m].
std::int64_t Ticks(double distance_m) {
  return static_cast<std::int64_t>(std::llround(distance_m / (2.0 * M_PI * 0.1 / 4096.0)));
}

// A straight drive at 0.4 m/s for 60 s after a 10 s standstill, encoders at 100 Hz and
// the gyro at 200 Hz reading the bias plus white noise; the wheel odometry's heading at
// the end [rad] (the truth: 0).
double HeadingAfterStraightDrive(const LocalizationOptions& options) {
  LocalizationStack stack(options, static_cast<const geometry::StereoCamera*>(nullptr),
                          Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity());
  random::Generator rng(3);
  const double dt = 0.005, per_sample = options.gyro_model.noise_density / std::sqrt(dt);
  const Eigen::Vector3d gravity(0.0, 0.0, 9.81);
  for (int k = 1; k <= 14000; ++k) {
    const double t = k * dt;
    const double moved = t > 10.0 ? 0.4 * (t - 10.0) : 0.0;
    if (k % 2 == 0) stack.AddEncoderSample(t, Ticks(moved), Ticks(moved));
    const Eigen::Vector3d white(rng.Gaussian(), rng.Gaussian(), rng.Gaussian());
    stack.AddImuSample(t, kBias + per_sample * white, gravity);
  }
  return geometry::PlanarPose(stack.wheel_odometry()).yaw;
}

TEST(GyroLedWheelOdometryTest, TheStandstillsBiasHoldsTheHeading) {
  LocalizationOptions options;
  options.gyro_model = TypicalGyro();
  // The tracks' speed difference: straight, exactly.
  EXPECT_NEAR(HeadingAfterStraightDrive(options), 0.0, 1e-12);
  options.gyro.wheel_rotation = true;
  // The gyro uncorrected turns with its bias over the whole 70 s: 0.175 rad, give or
  // take its angle random walk (N·√70 = 1.2e-3 rad).
  const double uncorrected = HeadingAfterStraightDrive(options);
  EXPECT_NEAR(uncorrected, kBias.z() * 70.0, 5e-3);
  options.gyro.zero_velocity_bias = true;
  // With the standstill's bias: the estimate's error (σ 4.5e-5 rad/s) over 60 s and the
  // white noise's angle random walk over 70 s, together σ = 3.0e-3 rad: within 4 σ.
  const double corrected = HeadingAfterStraightDrive(options);
  EXPECT_LT(std::abs(corrected), 1.2e-2);
  EXPECT_LT(std::abs(corrected), 0.1 * std::abs(uncorrected));
}

TEST(WheelOdometryTest, AGivenYawIncrementReplacesTheTracksDifference) {
  WheelOdometryOptions o;
  WheelOdometry wheels(o, {0.0, 0.0, 0.0});
  wheels.AddEncoderSample(0.0, 0, 0);
  // The left track faster than the right (a right turn by the tracks), the heading given.
  wheels.AddEncoderSample(0.1, 100, 60, 0.05);
  EXPECT_NEAR(wheels.pose().yaw, 0.05, 1e-15);
  EXPECT_NEAR(wheels.yaw_rate_radps(), 0.5, 1e-12);
  wheels.Rotate(-0.02);
  EXPECT_NEAR(wheels.pose().yaw, 0.03, 1e-15);
}

TEST(CovarianceFusionTest, ChiSquareQuantilesMatchTheTables) {
  EXPECT_NEAR(ChiSquareQuantile(1, 0.95), 3.8415, 1e-4);
  EXPECT_NEAR(ChiSquareQuantile(3, 0.95), 7.8147, 1e-4);
  EXPECT_NEAR(ChiSquareQuantile(3, 0.999), 16.2662, 1e-4);
}

TEST(CovarianceFusionTest, IncrementsCombineByTheirCovariances) {
  const geometry::Pose2 prediction{0.040, 0.000, 0.010}, measurement{0.044, 0.002, 0.014};
  const Eigen::Matrix3d Q = Eigen::Vector3d(1e-6, 4e-6, 1e-8).asDiagonal();
  const Eigen::Matrix3d R = Eigen::Vector3d(1e-6, 1e-6, 3e-8).asDiagonal();
  bool used = false;
  const geometry::Pose2 f = CombineIncrements(prediction, Q, measurement, R, 1e9, &used);
  EXPECT_TRUE(used);
  EXPECT_NEAR(f.x, 0.042, 1e-12);                  // equal variances: the mean
  EXPECT_NEAR(f.y, 0.002 * 4.0 / 5.0, 1e-12);      // the better-known measurement
  EXPECT_NEAR(f.yaw, 0.010 + 0.004 / 4.0, 1e-12);  // the better-known prediction
}

TEST(CovarianceFusionTest, AMeasurementBeyondTheGateIsLeftOut) {
  const geometry::Pose2 prediction{0.040, 0.000, 0.000};
  const Eigen::Matrix3d Q = Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal();
  const Eigen::Matrix3d R = Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal();
  const double gate = ChiSquareQuantile(3, 0.999);
  // A VO frame 3° off in yaw with a covariance that claims 0.006°: 370 σ.
  const geometry::Pose2 wrong{0.040, 0.000, 3.0 * M_PI / 180.0};
  CovarianceFusion fusion({0.0, 0.0, 0.0}, gate);
  EXPECT_FALSE(fusion.Add(prediction, Q, wrong, R));
  EXPECT_NEAR(fusion.pose().yaw, 0.0, 1e-15);
  EXPECT_NEAR(fusion.pose().x, 0.040, 1e-15);
  // One σ off: used.
  EXPECT_TRUE(fusion.Add(prediction, Q, geometry::Pose2{0.041, 0.0, 1e-4}, R));
  EXPECT_NEAR(fusion.pose().x, 0.080 + 0.0005, 1e-12);
}

}  // namespace
}  // namespace trackbed::estimation
