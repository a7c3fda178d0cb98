// A gyro's rotation over an interval that need not end at a sample: the rates held
// piecewise (each sample's rate over the interval since the sample before it, as
// LocalizationStack integrates them), cut at the interval's ends. Used to pair a
// stereo frame with the gyro at the instant it was exposed on the IMU's clock, the
// frame's stamp plus the camera–IMU time offset (calibration::ImuCalibration::
// camera_time_offset_s), which falls between samples.
#pragma once

#include <deque>

#include <Eigen/Core>

namespace trackbed::estimation {

/// One gyro sample: its body rate [rad/s], held over (t0_s, t1_s] (t1_s the sample's
/// time, t0_s the previous sample's).
struct GyroInterval {
  double t0_s = 0.0;
  double t1_s = 0.0;
  Eigen::Vector3d rate_radps = Eigen::Vector3d::Zero();
};

/// The body's rotation over (t0_s, t1_s] from the held rates, composed in time order
/// on the right (R = Exp(ω₁·Δ₁)·Exp(ω₂·Δ₂)·…, the body frame's): each interval counts
/// for its overlap with (t0_s, t1_s]. Before the first interval its rate is held, after
/// the last the last's (a gyro whose next sample has not come yet). The identity for
/// no intervals or t1_s <= t0_s. Intervals in time order, not overlapping.
Eigen::Matrix3d IntegrateGyro(const std::deque<GyroInterval>& intervals, double t0_s, double t1_s);

/// Drops the intervals that end at or before t_s (they lie wholly before it).
void DropGyroBefore(double t_s, std::deque<GyroInterval>* intervals);

}  // namespace trackbed::estimation
