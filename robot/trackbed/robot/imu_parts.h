// The IMU part each realism profile names, as its data sheet (and published Allan
// deviation measurements) describe it, and the noise model that reproduces it
// (docs/calibration.md gives every value's source). Temperature is left out: every
// figure is at constant temperature.
#pragma once

#include <string>
#include <vector>

#include "trackbed/robot/as_built.h"
#include "trackbed/robot/imu.h"

namespace trackbed::robot {

/// One sensor triad's noise as a data sheet states it.
struct ImuSensorSpec {
  /// White-noise density (angle or velocity random walk) [rad/s/√Hz or m/s²/√Hz].
  double noise_density = 0.0;
  /// Bias instability: the floor of the Allan deviation [rad/s or m/s²] (the data
  /// sheet's in-run bias stability, the minimum of its Allan deviation plot).
  double bias_instability = 0.0;
  /// Bias random walk (rate random walk) [rad/s²/√Hz or m/s³/√Hz].
  double bias_random_walk = 0.0;
  /// Turn-on bias, each axis' standard deviation [rad/s or m/s²].
  double turn_on_bias_std = 0.0;

  /// The Allan deviation the data sheet's numbers describe at averaging time `tau_s`
  /// (IEEE Std 952-1997, Annex C): √(N²/τ + B² + K²·τ/3), a flat floor B between the
  /// white noise's slope −½ and the rate random walk's +½.
  double AllanDeviation(double tau_s) const;
};

/// A named part: its gyro and accelerometer.
struct ImuPart {
  std::string name;
  ImuSensorSpec gyro, accel;
};

/// The profile's part: `ideal` the EuRoC ADIS16448 filter values (a bias random walk,
/// no instability floor), `typical` the ADIS16470, `harsh` the MPU-6000.
ImuPart ProfileImuPart(Realism profile);

/// Gauss–Markov correlation times [s] of the bias instability model: 1, 10, 100, 1000.
const std::vector<double>& BiasInstabilityTaus();

/// The stationary standard deviations of the Gauss–Markov terms (BiasInstabilityTaus)
/// whose summed Allan deviation is flat at `floor` within 3 % over τ = 3–2000 s (the
/// fit of scripts/imu_gauss_markov_fit.py): each a fixed multiple of `floor`.
std::vector<double> BiasInstabilityStds(double floor);

/// `imu` with every noise key it leaves out set to `part`'s.
ImuOptions WithImuPartResolved(ImuOptions imu, const ImuPart& part);
/// The same with the realism profile's part.
ImuOptions WithImuPartResolved(ImuOptions imu, Realism profile);

/// The Allan deviation of a first-order Gauss–Markov process of stationary standard
/// deviation `std` and correlation time `tau_c` at averaging time `tau_s`:
/// σ²(τ) = σ²·(2T/τ − (T/τ)²·(3 − 4e^{−τ/T} + e^{−2τ/T})).
double GaussMarkovAllanDeviation(double std, double tau_c, double tau_s);

}  // namespace trackbed::robot
