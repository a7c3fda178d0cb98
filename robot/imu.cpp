// IMU model (see imu.h). Continuous-time densities are discretised at the
// sampling period dt: white noise σ_d = σ_c / √dt, bias walk σ_d = σ_c · √dt.
#include "trackbed/robot/imu.h"

#include <cmath>

#include "trackbed/common/option_error.h"

namespace trackbed::robot {

void ImuOptions::Validate() const {
  option_check::InRange("rate_hz", rate_hz, 1.0, 10000.0);
  option_check::NonNegative("gyro_noise_density", gyro_noise_density);
  option_check::NonNegative("gyro_bias_random_walk", gyro_bias_random_walk);
  option_check::NonNegative("accel_noise_density", accel_noise_density);
  option_check::NonNegative("accel_bias_random_walk", accel_bias_random_walk);
  option_check::NonNegative("gyro_initial_bias_std", gyro_initial_bias_std);
  option_check::NonNegative("accel_initial_bias_std", accel_initial_bias_std);
}

Imu::Imu(const ImuOptions& options, double gravity_mps2, std::uint64_t seed,
         const calibration::ImuCalibration* as_built)
    : options_(options), gravity_mps2_(gravity_mps2), rng_(seed) {
  options_.Validate();
  if (as_built && !(as_built->IsIdentity() && as_built->accel_axes.isIdentity(0.0))) {
    as_built_ = *as_built;
  }
  gyro_bias_ = options_.gyro_initial_bias_std * Gaussian3();
  accel_bias_ = options_.accel_initial_bias_std * Gaussian3();
}

Eigen::Vector3d Imu::Gaussian3() {
  const double a = rng_.Gaussian(), b = rng_.Gaussian(), c = rng_.Gaussian();
  return {a, b, c};
}

ImuSample Imu::Sample(double t_s, const Eigen::Matrix3d& R_world_body,
                      const Eigen::Vector3d& omega_world, const Eigen::Vector3d& accel_world) {
  const double dt = 1.0 / options_.rate_hz;
  gyro_bias_ += options_.gyro_bias_random_walk * std::sqrt(dt) * Gaussian3();
  accel_bias_ += options_.accel_bias_random_walk * std::sqrt(dt) * Gaussian3();
  ImuSample s;
  s.t_s = t_s;
  const Eigen::Matrix3d R_body_world = R_world_body.transpose();
  Eigen::Vector3d rate = R_body_world * omega_world;
  Eigen::Vector3d specific_force =
      R_body_world * (accel_world + Eigen::Vector3d(0, 0, gravity_mps2_));
  if (as_built_) {
    // The sensor's axes as built (calibration::ImuCalibration's model).
    const Eigen::Matrix3d R_imu_body = as_built_->R_body_imu.transpose();
    const Eigen::Vector3d f_imu = R_imu_body * specific_force;
    rate = as_built_->gyro_axes * (R_imu_body * rate) + as_built_->gyro_g_sensitivity * f_imu;
    specific_force = as_built_->accel_axes * f_imu;
  }
  s.gyro_radps = rate + gyro_bias_ + options_.gyro_noise_density / std::sqrt(dt) * Gaussian3();
  s.accel_mps2 =
      specific_force + accel_bias_ + options_.accel_noise_density / std::sqrt(dt) * Gaussian3();
  s.gyro_bias = gyro_bias_;
  s.accel_bias = accel_bias_;
  return s;
}

}  // namespace trackbed::robot
