// The body's angular rate from an IMU's readings and its given calibration: the model
// of calibration::ImuCalibration (imu_calibration.json) solved for ω_body,
//   ω_body = R_body_imu · gyro_axes⁻¹ · (gyro − gyro_g_sensitivity · accel_axes⁻¹ · accel),
// with the matrices inverted once, not at every sample.
#pragma once

#include <Eigen/Core>

#include "trackbed/common/robot_calibration.h"

namespace trackbed::estimation {

class ImuCorrection {
 public:
  explicit ImuCorrection(const calibration::ImuCalibration& given)
      : identity_(given.IsIdentity()),
        rate_from_gyro_(given.R_body_imu * given.gyro_axes.inverse()),
        gyro_from_accel_(given.gyro_g_sensitivity * given.accel_axes.inverse()),
        force_from_accel_(given.R_body_imu * given.accel_axes.inverse()) {}

  /// Whether readings pass unchanged (a perfect IMU aligned with the body).
  bool identity() const { return identity_; }
  /// The body rate [rad/s] from a gyro reading and the accelerometer's reading of the
  /// same instant, in the IMU's axes (biases are the estimator's business).
  Eigen::Vector3d BodyRate(const Eigen::Vector3d& gyro, const Eigen::Vector3d& accel) const {
    if (identity_) return gyro;
    return rate_from_gyro_ * (gyro - gyro_from_accel_ * accel);
  }
  /// The specific force [m/s²] in the body's axes from an accelerometer reading in the
  /// IMU's (its bias left in).
  Eigen::Vector3d BodySpecificForce(const Eigen::Vector3d& accel) const {
    if (identity_) return accel;
    return force_from_accel_ * accel;
  }

 private:
  bool identity_;
  Eigen::Matrix3d rate_from_gyro_, gyro_from_accel_, force_from_accel_;
};

}  // namespace trackbed::estimation
