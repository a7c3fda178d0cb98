// A 6-axis IMU (3-axis gyro and accelerometer) on the chassis: per axis white noise,
// a bias random walk (rate random walk), a bias instability as a sum of first-order
// Gauss–Markov terms (bounded), and a turn-on bias; sampled at a fixed rate.
// Temperature is not modelled.
//
// A noise key left out takes the realism profile's part (WithImuPartResolved,
// robot/imu_parts.h; docs/calibration.md gives each value's source): under `ideal` the
// ADIS16448 as characterised for the EuRoC MAV dataset (Burri et al. 2016; Kalibr's
// imu.yaml): gyro noise density 1.6968e-4 rad/s/√Hz, gyro bias random walk 1.9393e-5
// rad/s²/√Hz, accel noise density 2.0e-3 m/s²/√Hz, accel bias random walk 3.0e-3
// m/s³/√Hz, no Gauss–Markov terms.
#pragma once

#include <Eigen/Geometry>

#include <optional>
#include <vector>

#include "trackbed/common/archive.h"
#include "trackbed/common/random.h"
#include "trackbed/common/robot_calibration.h"

namespace trackbed::robot {

struct ImuOptions {
  /// Sampling rate [Hz], > 0.
  double rate_hz = 200.0;
  /// Gyro white-noise density (angle random walk) [rad/s/√Hz], >= 0. Unset: the profile's.
  std::optional<double> gyro_noise_density;
  /// Gyro bias random walk (rate random walk) [rad/s²/√Hz], >= 0. Unset: the profile's.
  std::optional<double> gyro_bias_random_walk;
  /// Gyro bias instability: each first-order Gauss–Markov term's stationary standard
  /// deviation [rad/s] (>= 0) and correlation time [s] (> 0), lists of one length.
  /// Unset: the profile's.
  std::optional<std::vector<double>> gyro_bias_markov_std;
  std::optional<std::vector<double>> gyro_bias_markov_tau_s;
  /// Accelerometer white-noise density (velocity random walk) [m/s²/√Hz], >= 0.
  std::optional<double> accel_noise_density;
  /// Accelerometer bias random walk [m/s³/√Hz], >= 0.
  std::optional<double> accel_bias_random_walk;
  /// Accelerometer bias instability as Gauss–Markov terms: σ [m/s²] and τ [s].
  std::optional<std::vector<double>> accel_bias_markov_std;
  std::optional<std::vector<double>> accel_bias_markov_tau_s;
  /// Standard deviation of each axis' turn-on gyro bias [rad/s], >= 0.
  std::optional<double> gyro_initial_bias_std;
  /// Standard deviation of each axis' turn-on accelerometer bias [m/s²], >= 0.
  std::optional<double> accel_initial_bias_std;

  /// Throws OptionError naming the first field out of range, unset, or a Gauss–Markov
  /// list whose length differs from its partner's.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    constexpr archive::Field kOpt = archive::kOmitEmpty;
    a->Visit("rate_hz", &rate_hz);
    a->Visit("gyro_noise_density", &gyro_noise_density, kOpt);
    a->Visit("gyro_bias_random_walk", &gyro_bias_random_walk, kOpt);
    a->Visit("accel_noise_density", &accel_noise_density, kOpt);
    a->Visit("accel_bias_random_walk", &accel_bias_random_walk, kOpt);
    a->Visit("gyro_initial_bias_std", &gyro_initial_bias_std, kOpt);
    a->Visit("accel_initial_bias_std", &accel_initial_bias_std, kOpt);
    a->Visit("gyro_bias_markov_std", &gyro_bias_markov_std, kOpt);
    a->Visit("gyro_bias_markov_tau_s", &gyro_bias_markov_tau_s, kOpt);
    a->Visit("accel_bias_markov_std", &accel_bias_markov_std, kOpt);
    a->Visit("accel_bias_markov_tau_s", &accel_bias_markov_tau_s, kOpt);
  }
};

/// One IMU reading in the body frame.
struct ImuSample {
  double t_s = 0.0;
  Eigen::Vector3d gyro_radps = Eigen::Vector3d::Zero();  ///< Angular rate.
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();  ///< Specific force.
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   ///< True bias (ground truth).
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  ///< True bias (ground truth).
};

/// Turns the chassis' true motion into noisy IMU samples. Owns its random
/// generator, seeded explicitly. Not copyable.
class Imu {
 public:
  /// `options` must have every noise key set (WithImuPartResolved). `as_built`
  /// (robot/as_built.h): the IMU's scale factors, axes, g-sensitivity and
  /// mounting as built (the model of calibration::ImuCalibration); null: a perfect IMU
  /// aligned with the body. Its time offset is the camera's business, not the IMU's.
  Imu(const ImuOptions& options, double gravity_mps2, std::uint64_t seed,
      const calibration::ImuCalibration* as_built = nullptr);
  Imu(const Imu&) = delete;
  Imu& operator=(const Imu&) = delete;

  /// One sample at time `t_s` from the true orientation, angular velocity
  /// (world) and the mean linear acceleration (world) over the last period, in the
  /// IMU's own axes.
  ImuSample Sample(double t_s, const Eigen::Matrix3d& R_world_body,
                   const Eigen::Vector3d& omega_world, const Eigen::Vector3d& accel_world);

  const ImuOptions& options() const { return options_; }

  /// The Earth's rotation in the world's axes [rad/s] (sim::GeodeticOrigin::
  /// EarthRateInWorld): the gyro senses the body's rate against an inertial frame,
  /// the world's rate plus this. Not set: a world that does not turn.
  void SetEarthRate(const Eigen::Vector3d& omega_ie_world) { earth_rate_world_ = omega_ie_world; }

 private:
  // One first-order Gauss–Markov term per axis, discretised exactly at the sampling
  // period: b ← φ·b + σ·√(1 − φ²)·w, φ = exp(−dt/τ), started from its stationary law.
  struct MarkovTerm {
    double phi = 0.0, drive = 0.0;
    Eigen::Vector3d state = Eigen::Vector3d::Zero();
  };
  Eigen::Vector3d Gaussian3();
  std::vector<MarkovTerm> MarkovTerms(const std::vector<double>& std,
                                      const std::vector<double>& tau_s);
  Eigen::Vector3d StepMarkov(std::vector<MarkovTerm>* terms);

  ImuOptions options_;
  double gravity_mps2_;
  random::Generator rng_;
  // The random walk's and the white noise's per-sample standard deviations.
  double gyro_walk_step_ = 0.0, accel_walk_step_ = 0.0, gyro_white_ = 0.0, accel_white_ = 0.0;
  Eigen::Vector3d gyro_bias_, accel_bias_;  // turn-on bias plus the random walk
  std::vector<MarkovTerm> gyro_markov_, accel_markov_;
  std::optional<calibration::ImuCalibration> as_built_;  // none: perfect and aligned
  std::optional<Eigen::Vector3d> earth_rate_world_;      // none: the world does not turn
};

}  // namespace trackbed::robot
