// A 6-axis IMU (3-axis gyro and accelerometer) on the chassis, with white
// noise and a bias random walk, sampled at a fixed rate.
//
// Default magnitudes are those of the ADIS16448 as characterised for the EuRoC
// MAV dataset (Burri et al. 2016; Kalibr's imu.yaml): gyro noise density
// 1.6968e-4 rad/s/√Hz, gyro bias random walk 1.9393e-5 rad/s²/√Hz, accel noise
// density 2.0e-3 m/s²/√Hz, accel bias random walk 3.0e-3 m/s³/√Hz.
#pragma once

#include <Eigen/Geometry>

#include <optional>

#include "trackbed/common/random.h"
#include "trackbed/common/robot_calibration.h"

namespace trackbed::robot {

struct ImuOptions {
  /// Sampling rate [Hz], > 0.
  double rate_hz = 200.0;
  /// Gyro white-noise density [rad/s/√Hz], >= 0.
  double gyro_noise_density = 1.6968e-4;
  /// Gyro bias random walk [rad/s²/√Hz], >= 0.
  double gyro_bias_random_walk = 1.9393e-5;
  /// Accelerometer white-noise density [m/s²/√Hz], >= 0.
  double accel_noise_density = 2.0e-3;
  /// Accelerometer bias random walk [m/s³/√Hz], >= 0.
  double accel_bias_random_walk = 3.0e-3;
  /// Standard deviation of each axis' initial gyro bias [rad/s], >= 0.
  double gyro_initial_bias_std = 1e-3;
  /// Standard deviation of each axis' initial accelerometer bias [m/s²], >= 0.
  double accel_initial_bias_std = 2e-2;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("rate_hz", &rate_hz);
    a->Visit("gyro_noise_density", &gyro_noise_density);
    a->Visit("gyro_bias_random_walk", &gyro_bias_random_walk);
    a->Visit("accel_noise_density", &accel_noise_density);
    a->Visit("accel_bias_random_walk", &accel_bias_random_walk);
    a->Visit("gyro_initial_bias_std", &gyro_initial_bias_std);
    a->Visit("accel_initial_bias_std", &accel_initial_bias_std);
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
  /// `as_built` (robot/as_built.h): the IMU's scale factors, axes, g-sensitivity and
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

 private:
  Eigen::Vector3d Gaussian3();

  ImuOptions options_;
  double gravity_mps2_;
  random::Generator rng_;
  Eigen::Vector3d gyro_bias_, accel_bias_;
  std::optional<calibration::ImuCalibration> as_built_;  // none: perfect and aligned
};

}  // namespace trackbed::robot
