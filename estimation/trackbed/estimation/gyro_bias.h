// The gyro as a source of heading: what its data sheet says about it (GyroModel), its
// bias estimated from the intervals in which the robot stands still (zero-velocity
// updates, ZeroVelocityGyroBias), and the options that make it the rotation source of
// wheel odometry and of the fusion (GyroHeadingOptions; docs/localization.md, "The gyro
// as the rotation source").
//
// Standstill is detected from the encoders: neither track's count more than a tick from
// where it stood over the last `standstill_window_s` (a count toggles at a tick's edge as
// the chassis rocks on its suspension). The stack sees its sensor streams only, so it runs
// unchanged on logged data; unchanged counts on both sprockets bound the tracks' motion to under a
// tick, where a commanded zero twist says what the robot should do, not what it does
// (the sprocket servo settles after a stop, a robot stopped on a slope creeps).
#pragma once

#include <deque>

#include <Eigen/Core>

#include "trackbed/estimation/gyro_rotation.h"

namespace trackbed::estimation {

/// The gyro's noise as its data sheet gives it: what the software knows of its IMU
/// (the realism profile's part or the scenario's robot.imu keys; the runner fills it
/// in, no key). Every field >= 0.
struct GyroModel {
  /// White-noise density (angle random walk) [rad/s/√Hz].
  double noise_density = 1.6968e-4;
  /// Bias random walk (rate random walk) [rad/s²/√Hz].
  double bias_random_walk = 1.9393e-5;
  /// Standard deviation of the bias the estimate cannot follow [rad/s]: the bias
  /// instability's Gauss–Markov terms together at their stationary spread (0: none).
  double bias_instability_std = 0.0;
  /// Standard deviation of each axis' turn-on bias [rad/s]: the bias before any
  /// estimate.
  double turn_on_bias_std = 1e-3;

  void Validate() const;

  /// The variance of the gyro's rotation about one axis over `dt_s` [rad²] with a bias
  /// known to `bias_variance` [(rad/s)²]: (σ_b·dt)² + N²·dt, σ_b² = bias_variance +
  /// bias_instability_std².
  double RotationVariance(double dt_s, double bias_variance) const;
};

/// The keys of the gyro as a rotation source (the scenario's `estimation.gyro.*`,
/// docs/scenario_format.md). All off by default: the paper's configuration.
struct GyroHeadingOptions {
  /// Estimate the gyro's bias from the samples taken while the robot stands still
  /// (ZeroVelocityGyroBias) and take it off every rate the stack uses but the EKF's
  /// (which has its own bias state): the gyro-led heading and VO's rotation prior. Off:
  /// the gyro's rotation is used uncorrected.
  bool zero_velocity_bias = false;
  /// How long both encoders must have kept their counts before the robot counts as
  /// standing still [s], > 0.
  double standstill_window_s = 0.5;
  /// The gyro (bias-corrected, about the vertical the accelerometer finds) as the
  /// rotation source of the `wheel_odometry` estimator instead of the tracks' speed
  /// difference; VO's rotation enters it weighed by VO's covariance against the gyro's
  /// (GyroModel::RotationVariance), and the slip estimate takes its yaw rate from
  /// their combination at every valid frame.
  bool wheel_rotation = false;
  /// The gyro-led wheel odometry (as above) as the wheel increments of Ham et al.'s
  /// fusion (`fused`, or `fused_ham2012` beside the covariance fusion).
  bool fusion_rotation = false;
  /// Time constant of the low-pass on the accelerometer that finds the vertical [s],
  /// > 0: the heading rate is the body rate's component along it.
  double vertical_filter_time_s = 1.0;

  void Validate() const;

  /// The keys of these fields, read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("zero_velocity_bias", &zero_velocity_bias);
    a->Visit("standstill_window_s", &standstill_window_s);
    a->Visit("wheel_rotation", &wheel_rotation);
    a->Visit("fusion_rotation", &fusion_rotation);
    a->Visit("vertical_filter_time_s", &vertical_filter_time_s);
  }
};

/// The gyro's bias from zero-velocity intervals: per axis a Kalman filter of a constant
/// with the turn-on bias as its prior, a random walk of the data sheet's density as its
/// process, and each standstill sample a measurement of it with the white noise's
/// variance over its interval (N²/Δt). Over a standstill of T seconds from a wide prior
/// the estimate is the samples' time-weighted mean, its standard deviation N/√T.
class ZeroVelocityGyroBias {
 public:
  /// How far a count may toggle while the robot stands [ticks].
  static constexpr long long kStandstillTicks = 1;

  ZeroVelocityGyroBias(const GyroModel& model, double standstill_window_s);

  /// An encoder sample (counts since start): the robot stands still once neither count
  /// has moved more than kStandstillTicks from where it stood for the standstill window. It settles
  /// the gyro samples up to its time: each measures the bias when the robot still stands, else only
  /// advances the bias's random walk (a sample just before counts that changed may hold the
  /// motion's start).
  void AddEncoderSample(double t_s, long long left_ticks, long long right_ticks);
  /// A gyro sample: the body rate [rad/s] held over (t_prev, t_s], held until an encoder
  /// sample at or after t_s settles it. A standstill sample with a rate beyond five σ of
  /// its white noise plus three turn-on σ on any axis is motion the encoders do not see
  /// (the chassis settling on its suspension) and is not used.
  void AddGyroSample(double t_s, const Eigen::Vector3d& rate_radps);

  /// Whether the latest encoder sample found the robot standing still (counts unchanged
  /// for the window).
  bool standstill() const { return standstill_; }
  /// The bias estimate [rad/s] and its variance per axis [(rad/s)²].
  const Eigen::Vector3d& bias() const { return bias_; }
  const Eigen::Vector3d& variance() const { return variance_; }
  /// Seconds of standstill samples used so far (settled ones).
  double standstill_s() const { return standstill_s_; }

 private:
  void Use(const GyroInterval& sample);

  GyroModel model_;
  double window_s_;
  Eigen::Vector3d bias_ = Eigen::Vector3d::Zero(), variance_;
  bool standstill_ = false, has_encoder_ = false, has_gyro_ = false;
  long long left_ = 0, right_ = 0;
  double t_counts_changed_ = 0.0, t_gyro_ = 0.0, standstill_s_ = 0.0;
  std::deque<GyroInterval> pending_;  // gyro samples no encoder sample has settled yet
};

}  // namespace trackbed::estimation
