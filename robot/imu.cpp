// IMU model (see imu.h). Continuous-time densities are discretised at the
// sampling period dt: white noise σ_d = σ_c / √dt, bias walk σ_d = σ_c · √dt; each
// Gauss–Markov term exactly (imu.h, MarkovTerm).
#include "trackbed/robot/imu.h"

#include <cmath>
#include <string>

#include "trackbed/common/option_error.h"

namespace trackbed::robot {
namespace {

// A value the realism profile's part fills in: set, and not negative.
void CheckSetNonNegative(const char* field, const std::optional<double>& v) {
  if (!v) throw OptionError(field, "not set (WithImuPartResolved gives the profile's)");
  option_check::NonNegative(field, *v);
}

void CheckMarkov(const char* std_field, const char* tau_field,
                 const std::optional<std::vector<double>>& std,
                 const std::optional<std::vector<double>>& tau_s) {
  if (!std) throw OptionError(std_field, "not set (WithImuPartResolved gives the profile's)");
  if (!tau_s) throw OptionError(tau_field, "not set (WithImuPartResolved gives the profile's)");
  if (std->size() != tau_s->size()) {
    throw OptionError(tau_field, "must have as many entries as " + std::string(std_field) + " (" +
                                     std::to_string(std->size()) + "), got " +
                                     std::to_string(tau_s->size()));
  }
  for (std::size_t k = 0; k < std->size(); ++k) {
    const std::string i = "[" + std::to_string(k) + "]";
    option_check::NonNegative((std_field + i).c_str(), (*std)[k]);
    option_check::InRange((tau_field + i).c_str(), (*tau_s)[k], 1e-6, 1e9);
  }
}

}  // namespace

void ImuOptions::Validate() const {
  option_check::InRange("rate_hz", rate_hz, 1.0, 10000.0);
  CheckSetNonNegative("gyro_noise_density", gyro_noise_density);
  CheckSetNonNegative("gyro_bias_random_walk", gyro_bias_random_walk);
  CheckSetNonNegative("accel_noise_density", accel_noise_density);
  CheckSetNonNegative("accel_bias_random_walk", accel_bias_random_walk);
  CheckSetNonNegative("gyro_initial_bias_std", gyro_initial_bias_std);
  CheckSetNonNegative("accel_initial_bias_std", accel_initial_bias_std);
  CheckMarkov("gyro_bias_markov_std", "gyro_bias_markov_tau_s", gyro_bias_markov_std,
              gyro_bias_markov_tau_s);
  CheckMarkov("accel_bias_markov_std", "accel_bias_markov_tau_s", accel_bias_markov_std,
              accel_bias_markov_tau_s);
}

Imu::Imu(const ImuOptions& options, double gravity_mps2, std::uint64_t seed,
         const calibration::ImuCalibration* as_built)
    : options_(options), gravity_mps2_(gravity_mps2), rng_(seed) {
  options_.Validate();
  if (as_built && !(as_built->IsIdentity() && as_built->accel_axes.isIdentity(0.0))) {
    as_built_ = *as_built;
  }
  const double dt = 1.0 / options_.rate_hz;
  gyro_walk_step_ = *options_.gyro_bias_random_walk * std::sqrt(dt);
  accel_walk_step_ = *options_.accel_bias_random_walk * std::sqrt(dt);
  gyro_white_ = *options_.gyro_noise_density / std::sqrt(dt);
  accel_white_ = *options_.accel_noise_density / std::sqrt(dt);
  gyro_bias_ = *options_.gyro_initial_bias_std * Gaussian3();
  accel_bias_ = *options_.accel_initial_bias_std * Gaussian3();
  gyro_markov_ = MarkovTerms(*options_.gyro_bias_markov_std, *options_.gyro_bias_markov_tau_s);
  accel_markov_ = MarkovTerms(*options_.accel_bias_markov_std, *options_.accel_bias_markov_tau_s);
}

Eigen::Vector3d Imu::Gaussian3() {
  const double a = rng_.Gaussian(), b = rng_.Gaussian(), c = rng_.Gaussian();
  return {a, b, c};
}

std::vector<Imu::MarkovTerm> Imu::MarkovTerms(const std::vector<double>& std,
                                              const std::vector<double>& tau_s) {
  std::vector<MarkovTerm> terms;
  const double dt = 1.0 / options_.rate_hz;
  for (std::size_t k = 0; k < std.size(); ++k) {
    if (std[k] == 0.0) continue;  // a silent term draws nothing
    MarkovTerm t;
    t.phi = std::exp(-dt / tau_s[k]);
    t.drive = std[k] * std::sqrt(-std::expm1(-2.0 * dt / tau_s[k]));  // σ·√(1 − φ²)
    t.state = std[k] * Gaussian3();
    terms.push_back(t);
  }
  return terms;
}

Eigen::Vector3d Imu::StepMarkov(std::vector<MarkovTerm>* terms) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (MarkovTerm& t : *terms) {
    t.state = t.phi * t.state + t.drive * Gaussian3();
    sum += t.state;
  }
  return sum;
}

ImuSample Imu::Sample(double t_s, const Eigen::Matrix3d& R_world_body,
                      const Eigen::Vector3d& omega_world, const Eigen::Vector3d& accel_world) {
  // A zero random walk draws nothing; a non-zero one draws in the order it always has.
  if (gyro_walk_step_ != 0.0) gyro_bias_ += gyro_walk_step_ * Gaussian3();
  if (accel_walk_step_ != 0.0) accel_bias_ += accel_walk_step_ * Gaussian3();
  Eigen::Vector3d gyro_bias = gyro_bias_, accel_bias = accel_bias_;
  if (!gyro_markov_.empty()) gyro_bias += StepMarkov(&gyro_markov_);
  if (!accel_markov_.empty()) accel_bias += StepMarkov(&accel_markov_);
  ImuSample s;
  s.t_s = t_s;
  const Eigen::Matrix3d R_body_world = R_world_body.transpose();
  Eigen::Vector3d rate =
      R_body_world *
      (earth_rate_world_ ? Eigen::Vector3d(omega_world + *earth_rate_world_) : omega_world);
  Eigen::Vector3d specific_force =
      R_body_world * (accel_world + Eigen::Vector3d(0, 0, gravity_mps2_));
  if (as_built_) {
    // The sensor's axes as built (calibration::ImuCalibration's model).
    const Eigen::Matrix3d R_imu_body = as_built_->R_body_imu.transpose();
    const Eigen::Vector3d f_imu = R_imu_body * specific_force;
    rate = as_built_->gyro_axes * (R_imu_body * rate) + as_built_->gyro_g_sensitivity * f_imu;
    specific_force = as_built_->accel_axes * f_imu;
  }
  s.gyro_radps = rate + gyro_bias + gyro_white_ * Gaussian3();
  s.accel_mps2 = specific_force + accel_bias + accel_white_ * Gaussian3();
  s.gyro_bias = gyro_bias;
  s.accel_bias = accel_bias;
  return s;
}

}  // namespace trackbed::robot
