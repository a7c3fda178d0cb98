// The EKF baseline (estimation/ekf_odometry.h) on synthetic planar motion: a
// unicycle truth integrated finely, with the gyro at 200 Hz, the wheels at 100 Hz
// and visual odometry's frame-to-frame motion at 10 Hz read off the truth, each
// corrupted the way the test says.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "trackbed/estimation/ekf_odometry.h"

namespace trackbed::estimation {
namespace {

constexpr double kDegPerRad = 180.0 / M_PI;

// Body-frame twist of the truth at t: forward, lateral [m/s], yaw rate [rad/s].
struct Twist {
  double vx = 0.0, vy = 0.0, omega = 0.0;
};

struct Corruption {
  double gyro_bias = 0.0;        // [rad/s]
  double gyro_noise = 0.0;       // per sample [rad/s]
  double wheel_yaw_scale = 1.0;  // skid: the wheels' yaw rate is this times the truth's
  double wheel_speed_scale = 1.0;
  double vo_noise = 0.0;                            // per frame, translation [m] and rotation [rad]
  double vo_yaw_noise = 0.0;                        // per frame, more rotation noise [rad]
  bool report_vo_covariance = false;                // each frame with its noise's covariance
  double vo_gap_from_s = -1.0, vo_gap_to_s = -1.0;  // frames without a motion
};

struct Result {
  geometry::Pose2 truth, estimate;
  double bias = 0.0;
  double truth_yaw_unwrapped = 0.0;  // the truth's yaw rate integrated [rad]
  double wheel_only_yaw = 0.0;       // the wheels' yaw rate integrated alone [rad]
};

Result Simulate(const std::function<Twist(double)>& twist, double duration_s, const Corruption& c,
                const EkfOdometryOptions& options = {}) {
  EkfOdometry ekf(options, {});
  std::mt19937 rng(7);
  std::normal_distribution<double> unit(0.0, 1.0);
  Result r;
  geometry::Pose2 at_frame;
  const double dt = 0.001;  // truth integration step; sensors on multiples of it
  const int n = static_cast<int>(std::lround(duration_s / dt));
  for (int k = 1; k <= n; ++k) {
    const double t = k * dt;
    const Twist v = twist(t - 0.5 * dt);
    r.truth = Compose(r.truth, {v.vx * dt, v.vy * dt, v.omega * dt});
    r.truth_yaw_unwrapped += v.omega * dt;
    const Twist now = twist(t);
    if (k % 5 == 0) ekf.AddGyro(t, now.omega + c.gyro_bias + c.gyro_noise * unit(rng));
    if (k % 10 == 0) {
      const double wheel_yaw = c.wheel_yaw_scale * now.omega;
      ekf.AddWheelTwist(t, c.wheel_speed_scale * now.vx, wheel_yaw);
      r.wheel_only_yaw += wheel_yaw * 0.01;
    }
    if (k % 100 == 0) {
      const bool gap = t > c.vo_gap_from_s && t <= c.vo_gap_to_s;
      geometry::Pose2 motion = Between(at_frame, r.truth);
      motion.x += c.vo_noise * unit(rng);
      motion.y += c.vo_noise * unit(rng);
      motion.yaw += c.vo_noise * unit(rng);
      motion.yaw += c.vo_yaw_noise * unit(rng);
      const double yaw_var = c.vo_noise * c.vo_noise + c.vo_yaw_noise * c.vo_yaw_noise;
      const Eigen::Matrix3d covariance =
          Eigen::Vector3d(c.vo_noise * c.vo_noise, c.vo_noise * c.vo_noise, yaw_var).asDiagonal();
      ekf.AddCameraFrame(t, gap ? std::nullopt : std::optional<geometry::Pose2>(motion), 150,
                         c.report_vo_covariance ? &covariance : nullptr);
      at_frame = r.truth;
    }
  }
  r.estimate = ekf.pose();
  r.bias = ekf.gyro_bias();
  return r;
}

double PositionError(const Result& r) {
  return std::hypot(r.estimate.x - r.truth.x, r.estimate.y - r.truth.y);
}
double HeadingErrorDeg(const Result& r) {
  return std::abs(geometry::WrapAngle(r.estimate.yaw - r.truth.yaw)) * kDegPerRad;
}

double Ramp(double s) { return std::clamp(s / 0.3, 0.0, 1.0); }

// 0.4 m/s with turns that start and stop within 0.3 s (yaw acceleration 2 rad/s²):
// left at 0.6 rad/s for 3 s, straight, right, straight; every 10 s.
Twist SlalomWithRamps(double t) {
  const double phase = std::fmod(t, 10.0);
  double omega = 0.0;
  if (phase < 3.0) {
    omega = 0.6 * Ramp(phase) * Ramp(3.0 - phase);
  } else if (phase >= 5.0 && phase < 8.0) {
    omega = -0.6 * Ramp(phase - 5.0) * Ramp(8.0 - phase);
  }
  return {0.4, 0.0, omega};
}

// The same turns, all to the left: a skid's extra yaw does not cancel.
Twist LeftLoops(double t) {
  const double phase = std::fmod(t, 5.0);
  return {0.4, 0.0, phase < 3.0 ? 0.6 * Ramp(phase) * Ramp(3.0 - phase) : 0.0};
}

// Not wrapped: a skid's extra yaw over many loops exceeds half a turn.
double WheelOnlyHeadingErrorDeg(const Result& r) {
  return std::abs(r.wheel_only_yaw - r.truth_yaw_unwrapped) * kDegPerRad;
}

TEST(EkfOdometryTest, ExactSensorsGiveTheTruth) {
  const Result r = Simulate(SlalomWithRamps, 30.0, {});
  // What is left is the sample-and-hold of the rates between sensor samples.
  EXPECT_LT(PositionError(r), 5e-3) << PositionError(r);
  EXPECT_LT(HeadingErrorDeg(r), 0.1) << HeadingErrorDeg(r);
}

TEST(EkfOdometryTest, TurnsThatStartAndStopDoNotLeakIntoTheGyroBias) {
  // A frame's motion is the mean over its interval; while the turn rate ramps it
  // differs from the rate at the frame's end by up to 0.1 rad/s. Read as a rate it
  // would be explained as gyro bias (2.4e-4 rad/s after this run, when it was).
  const Result r = Simulate(SlalomWithRamps, 30.0, {});
  EXPECT_LT(std::abs(r.bias), 5e-5) << r.bias;
}

TEST(EkfOdometryTest, HeadingFollowsTheGyroAndVisionNotTheSkiddingWheels) {
  Corruption c;
  c.gyro_bias = 2e-3;
  c.gyro_noise = 2.4e-3;       // the IMU's noise density at 200 Hz
  c.wheel_yaw_scale = 1.2;     // skid turns: 20 % too much yaw
  c.wheel_speed_scale = 1.03;  // and 3 % too much distance
  c.vo_noise = 5e-4;
  const Result r = Simulate(LeftLoops, 60.0, c);
  ASSERT_GT(WheelOnlyHeadingErrorDeg(r), 90.0);
  EXPECT_LT(HeadingErrorDeg(r), 0.5);
  EXPECT_NEAR(r.bias, 2e-3, 3e-4);
  EXPECT_LT(PositionError(r), 0.1);
}

TEST(EkfOdometryTest, BridgesACameraGapOnTheGyro) {
  Corruption c;
  c.gyro_bias = 1e-3;
  c.wheel_yaw_scale = 1.2;
  c.vo_gap_from_s = 20.0;  // two turns without vision, at the end
  c.vo_gap_to_s = 30.0;
  const Result r = Simulate(LeftLoops, 30.0, c);
  ASSERT_GT(WheelOnlyHeadingErrorDeg(r), 90.0);
  EXPECT_LT(HeadingErrorDeg(r), 1.0);
  EXPECT_LT(PositionError(r), 0.3);
}

TEST(EkfOdometryTest, VisionsOwnCovarianceKeepsAPoorlyConditionedRotationOutOfTheBias) {
  // VO's rotation 0.02 rad off per frame (few or far features), its translation fine;
  // the inlier count (150) calls it good, and the gyro's bias state takes in its
  // noise. With VO's own covariance the gyro's bias stays at the truth (0) and the
  // position follows.
  Corruption c;
  c.gyro_noise = 2.4e-3;
  c.vo_noise = 5e-4;
  c.vo_yaw_noise = 0.02;
  c.report_vo_covariance = true;
  const Result by_inliers = Simulate(LeftLoops, 60.0, c);
  EkfOdometryOptions own;
  own.vo_covariance_from_vo = true;
  const Result by_covariance = Simulate(LeftLoops, 60.0, c, own);
  EXPECT_GT(std::abs(by_inliers.bias), 1e-3);
  EXPECT_LT(std::abs(by_covariance.bias), 2e-4);
  EXPECT_LT(PositionError(by_covariance), 0.5 * PositionError(by_inliers));
  EXPECT_LT(HeadingErrorDeg(by_covariance), 0.5);
}

TEST(EkfOdometryTest, SideSlipThatVisionSeesEntersThePosition) {
  // Crabbing down a slope at 0.05 m/s while the wheels report none.
  const auto crab = [](double) { return Twist{0.4, 0.05, 0.0}; };
  const Result r = Simulate(crab, 20.0, {});
  ASSERT_NEAR(r.truth.y, 1.0, 1e-9);
  EXPECT_LT(PositionError(r), 0.05);
}

}  // namespace
}  // namespace trackbed::estimation
