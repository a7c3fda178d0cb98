// A baseline none of the papers has: an extended Kalman filter fusing wheel
// odometry, the IMU's gyro and visual odometry with their covariances, in the
// manner of ROS's robot_localization (planar constant-velocity model, every
// sensor a measurement of part of the state).
//
// State: x, y [m], heading θ [rad], forward speed v [m/s], yaw rate ω [rad/s],
// gyro bias b [rad/s]. Prediction: constant velocity. Measurements: wheel
// odometry's (v, ω) from the encoders with B_eff (no slip model: slip shows up
// as disagreement with the other sensors), the gyro's ω + b, and visual
// odometry's (v, ω) over each valid frame interval.
#pragma once

#include <Eigen/Core>

#include "trackbed/estimation/pose2.h"

namespace trackbed::estimation {

struct EkfOdometryOptions {
  /// Process noise: forward acceleration [m/s²/√Hz] and yaw acceleration [rad/s²/√Hz].
  double accel_noise = 0.5;
  double yaw_accel_noise = 1.0;
  /// Gyro bias random walk [rad/s/√s].
  double gyro_bias_walk = 1e-4;
  /// Wheel odometry twist noise: standard deviations [m/s], [rad/s] per measurement.
  double wheel_speed_std = 0.03;
  double wheel_yaw_rate_std = 0.05;
  /// Gyro noise per sample [rad/s].
  double gyro_std = 0.005;
  /// Visual odometry twist noise at `vo_reference_inliers` inliers [m/s], [rad/s]; it
  /// grows as √(reference / inliers) with fewer.
  double vo_speed_std = 0.01;
  double vo_yaw_rate_std = 0.01;
  double vo_reference_inliers = 100.0;

  void Validate() const;
};

/// Not copyable; feed measurements in time order.
class EkfOdometry {
 public:
  EkfOdometry(const EkfOdometryOptions& options, const Pose2& initial_pose);
  EkfOdometry(const EkfOdometry&) = delete;
  EkfOdometry& operator=(const EkfOdometry&) = delete;

  /// Wheel-odometry twist at t (encoder speeds over the last sample interval).
  void AddWheelTwist(double t_s, double forward_mps, double yaw_rate_radps);
  /// Gyro z rate at t [rad/s].
  void AddGyro(double t_s, double yaw_rate_radps);
  /// Visual-odometry twist averaged over the frame interval ending at t.
  void AddVisualTwist(double t_s, double forward_mps, double yaw_rate_radps, int inliers);

  Pose2 pose() const { return {x_(0), x_(1), WrapAngle(x_(2))}; }
  double gyro_bias() const { return x_(5); }

 private:
  using Vec = Eigen::Matrix<double, 6, 1>;
  using Mat = Eigen::Matrix<double, 6, 6>;
  void PredictTo(double t_s);
  template <int M>
  void Update(const Eigen::Matrix<double, M, 1>& z, const Eigen::Matrix<double, M, 6>& H,
              const Eigen::Matrix<double, M, M>& R);

  EkfOdometryOptions options_;
  Vec x_ = Vec::Zero();
  Mat P_ = Mat::Zero();
  double t_ = 0.0;
  bool started_ = false;
};

}  // namespace trackbed::estimation
