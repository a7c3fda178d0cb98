// The realism profiles' IMU parts (see imu_parts.h); docs/calibration.md lists each
// value with its source.
#include "trackbed/robot/imu_parts.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "trackbed/common/units.h"

namespace trackbed::robot {
namespace {

double DegPerHour(double v) { return units::Radians(v) / 3600.0; }
double DegPerSecondPerRootHz(double v) { return units::Radians(v); }
double MicroG(double v) { return v * 1e-6 * units::kStandardGravity; }

// scripts/imu_gauss_markov_fit.py: least squares of the summed Allan variance of four
// Gauss–Markov terms (τ = 1, 10, 100, 1000 s) on a flat floor over τ = 1–3000 s.
constexpr double kFloorMultiples[] = {1.466599, 1.254594, 1.256696, 1.468278};

}  // namespace

double ImuSensorSpec::AllanDeviation(double tau_s) const {
  const double n = noise_density, b = bias_instability, k = bias_random_walk;
  return std::sqrt(n * n / tau_s + b * b + k * k * tau_s / 3.0);
}

ImuPart ProfileImuPart(Realism profile) {
  ImuPart p;
  // The turn-on bias of every profile: no data sheet repeatability at hand
  // (docs/calibration.md).
  p.gyro.turn_on_bias_std = 1e-3;
  p.accel.turn_on_bias_std = 2e-2;
  switch (profile) {
    case Realism::kIdeal:
      p.name = "EuRoC ADIS16448 (filter values)";
      p.gyro.noise_density = 1.6968e-4;
      p.gyro.bias_random_walk = 1.9393e-5;
      p.accel.noise_density = 2.0e-3;
      p.accel.bias_random_walk = 3.0e-3;
      break;
    case Realism::kTypical:
      p.name = "ADIS16470";
      p.gyro.noise_density = DegPerSecondPerRootHz(0.008);  // rate noise density
      p.gyro.bias_instability = DegPerHour(8.0);            // in-run bias stability
      p.accel.noise_density = 2.0e-3;                       // EuRoC's ADIS16448
      p.accel.bias_instability = MicroG(13.0);              // in-run bias stability
      break;
    case Realism::kHarsh:
      p.name = "MPU-6000";
      p.gyro.noise_density = DegPerSecondPerRootHz(0.005);  // rate noise spectral density
      p.gyro.bias_instability = DegPerHour(4.6);            // Greenheck 2009, Allan
      p.accel.noise_density = MicroG(400.0);                // power spectral density
      p.accel.bias_instability = MicroG(36.0);              // Greenheck 2009, Allan
      break;
  }
  return p;
}

const std::vector<double>& BiasInstabilityTaus() {
  static const std::vector<double> taus = {1.0, 10.0, 100.0, 1000.0};
  return taus;
}

std::vector<double> BiasInstabilityStds(double floor) {
  std::vector<double> stds;
  for (const double c : kFloorMultiples) stds.push_back(c * floor);
  return stds;
}

ImuOptions WithImuPartResolved(ImuOptions imu, const ImuPart& part) {
  const auto markov = [](double floor) {
    return floor > 0.0 ? BiasInstabilityStds(floor) : std::vector<double>{};
  };
  const auto taus = [](double floor) {
    return floor > 0.0 ? BiasInstabilityTaus() : std::vector<double>{};
  };
  if (!imu.gyro_noise_density) imu.gyro_noise_density = part.gyro.noise_density;
  if (!imu.gyro_bias_random_walk) imu.gyro_bias_random_walk = part.gyro.bias_random_walk;
  if (!imu.gyro_bias_markov_std) imu.gyro_bias_markov_std = markov(part.gyro.bias_instability);
  if (!imu.gyro_bias_markov_tau_s) imu.gyro_bias_markov_tau_s = taus(part.gyro.bias_instability);
  if (!imu.accel_noise_density) imu.accel_noise_density = part.accel.noise_density;
  if (!imu.accel_bias_random_walk) imu.accel_bias_random_walk = part.accel.bias_random_walk;
  if (!imu.accel_bias_markov_std) imu.accel_bias_markov_std = markov(part.accel.bias_instability);
  if (!imu.accel_bias_markov_tau_s) {
    imu.accel_bias_markov_tau_s = taus(part.accel.bias_instability);
  }
  if (!imu.gyro_initial_bias_std) imu.gyro_initial_bias_std = part.gyro.turn_on_bias_std;
  if (!imu.accel_initial_bias_std) imu.accel_initial_bias_std = part.accel.turn_on_bias_std;
  return imu;
}

ImuOptions WithImuPartResolved(ImuOptions imu, Realism profile) {
  return WithImuPartResolved(std::move(imu), ProfileImuPart(profile));
}

double GaussMarkovAllanDeviation(double std, double tau_c, double tau_s) {
  const double r = tau_c / tau_s, x = tau_s / tau_c;
  const double shape = 2.0 * r - r * r * (3.0 - 4.0 * std::exp(-x) + std::exp(-2.0 * x));
  return std * std::sqrt(std::max(shape, 0.0));
}

}  // namespace trackbed::robot
