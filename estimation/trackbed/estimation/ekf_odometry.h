// A baseline none of the papers has: an extended Kalman filter fusing wheel
// odometry, the IMU's gyro and visual odometry with their covariances, in the
// manner of ROS's robot_localization (planar constant-velocity model, every
// sensor a measurement of part of the state).
//
// State: x, y [m], heading θ [rad], body velocity v_x (forward), v_y (left) [m/s],
// yaw rate ω [rad/s], gyro bias b [rad/s], and a clone of (x, y, θ) taken at the
// last camera frame. Prediction: constant velocity. Measurements: wheel odometry's
// (v_x, v_y = 0, ω) from the encoders with B_eff (no slip model: slip shows up as
// disagreement with the other sensors), the gyro's ω + b, and visual odometry's
// planar motion between two frames as the pose's change since the clone
// (stochastic cloning, Roumeliotis & Burdick 2002).
//
// Why the clone: a VO frame gives the motion over the whole frame interval, not a
// rate at the frame's time. Read as the yaw rate at the frame's end, it lags the
// gyro by half an interval whenever the turn rate changes, and the filter put that
// disagreement into the gyro bias: outdoors (seed 1) the heading ended 14° off with
// VO itself 0.2° off (docs/localization.md).
//
// Why the wheel noise is large: skid-steer odometry's errors are slip, which
// persists over a manoeuvre (about a second), not white noise at the encoder rate.
// The defaults are the per-sample error RMS measured outdoors (0.018 m/s, 0.048
// rad/s at 100 Hz) times √(1 s / 0.01 s) = 10, the inflation that gives a white
// sequence at 100 Hz the same weight per second as one measurement per correlation
// time. The tracks' lateral slip (up to 0.08 m/s on slopes) lasts the whole run, so
// v_y = 0 is a loose constraint.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "trackbed/common/pose2.h"

namespace trackbed::estimation {

struct EkfOdometryOptions {
  /// Process noise: forward and lateral acceleration [m/s²/√Hz] and yaw acceleration
  /// [rad/s²/√Hz].
  double accel_noise = 0.5;
  double lateral_accel_noise = 0.5;
  double yaw_accel_noise = 1.0;
  /// Gyro bias random walk [rad/s/√s].
  double gyro_bias_walk = 1e-4;
  /// Wheel odometry twist noise: standard deviations per measurement, forward [m/s],
  /// lateral (the no-side-slip constraint) [m/s], yaw rate [rad/s].
  double wheel_speed_std = 0.2;
  double wheel_lateral_speed_std = 1.0;
  double wheel_yaw_rate_std = 0.5;
  /// Gyro noise per sample [rad/s].
  double gyro_std = 0.005;
  /// Visual odometry noise at `vo_reference_inliers` inliers, as a rate: a frame's
  /// translation (per axis) has σ = vo_speed_std · Δt [m], its rotation
  /// σ = vo_yaw_rate_std · Δt [rad]; both grow as √(reference / inliers) with fewer.
  double vo_speed_std = 0.01;
  double vo_yaw_rate_std = 0.01;
  double vo_reference_inliers = 100.0;
  /// Take a VO frame's noise from VO's own covariance (its planar part,
  /// docs/localization.md "Covariance") where the frame has one, rather than from the
  /// three figures above; a frame without one falls back on them. Off: the inlier-count
  /// model above.
  bool vo_covariance_from_vo = false;
  /// While the robot stands still (both encoders unchanged, gyro_bias.h), a
  /// measurement of zero velocity and yaw rate, so that the gyro's samples observe its
  /// bias (zero-velocity updates). Off: the wheels' twist only.
  bool zero_velocity_updates = false;
  /// The zero-velocity measurement's standard deviation, speeds [m/s] and yaw rate
  /// [rad/s], > 0.
  double zero_velocity_std = 1e-4;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("accel_noise", &accel_noise);
    a->Visit("lateral_accel_noise", &lateral_accel_noise);
    a->Visit("yaw_accel_noise", &yaw_accel_noise);
    a->Visit("gyro_bias_walk", &gyro_bias_walk);
    a->Visit("wheel_speed_std", &wheel_speed_std);
    a->Visit("wheel_lateral_speed_std", &wheel_lateral_speed_std);
    a->Visit("wheel_yaw_rate_std", &wheel_yaw_rate_std);
    a->Visit("gyro_std", &gyro_std);
    a->Visit("vo_speed_std", &vo_speed_std);
    a->Visit("vo_yaw_rate_std", &vo_yaw_rate_std);
    a->Visit("vo_reference_inliers", &vo_reference_inliers);
    a->Visit("vo_covariance_from_vo", &vo_covariance_from_vo);
    a->Visit("zero_velocity_updates", &zero_velocity_updates);
    a->Visit("zero_velocity_std", &zero_velocity_std);
  }
};

/// Not copyable; feed measurements in time order.
class EkfOdometry {
 public:
  EkfOdometry(const EkfOdometryOptions& options, const geometry::Pose2& initial_pose);
  EkfOdometry(const EkfOdometry&) = delete;
  EkfOdometry& operator=(const EkfOdometry&) = delete;

  /// Wheel-odometry twist at t (encoder speeds over the last sample interval).
  void AddWheelTwist(double t_s, double forward_mps, double yaw_rate_radps);
  /// Gyro z rate at t [rad/s].
  void AddGyro(double t_s, double yaw_rate_radps);
  /// The robot stands still at t: zero forward, lateral and yaw rate, each with
  /// σ = zero_velocity_std.
  void AddZeroVelocity(double t_s);
  /// A camera frame at t. `motion`: visual odometry's planar motion since the previous
  /// frame, in that frame's body axes, or none (a failed frame, or the first). Either
  /// way the pose now is what the next frame's motion starts from. `covariance`: the motion's own
  /// covariance of (x, y, yaw) [m², m·rad, rad²], used with vo_covariance_from_vo (may be null).
  void AddCameraFrame(double t_s, const std::optional<geometry::Pose2>& motion, int inliers,
                      const Eigen::Matrix3d* covariance = nullptr);

  geometry::Pose2 pose() const { return {x_(0), x_(1), geometry::WrapAngle(x_(2))}; }
  double gyro_bias() const { return x_(6); }
  /// The covariance of pose() (x, y, yaw) [m², m·rad, rad²]: the filter's own.
  Eigen::Matrix3d pose_covariance() const { return P_.topLeftCorner<3, 3>(); }

 private:
  static constexpr int kN = 10;
  using Vec = Eigen::Matrix<double, kN, 1>;
  using Mat = Eigen::Matrix<double, kN, kN>;
  void PredictTo(double t_s);
  template <int M>
  void Update(const Eigen::Matrix<double, M, 1>& innovation, const Eigen::Matrix<double, M, kN>& H,
              const Eigen::Matrix<double, M, M>& R);
  void ClonePose();

  EkfOdometryOptions options_;
  Vec x_ = Vec::Zero();
  Mat P_ = Mat::Zero();
  double t_ = 0.0;
  bool started_ = false;
  double t_clone_ = 0.0;
  bool has_clone_ = false;
};

}  // namespace trackbed::estimation
