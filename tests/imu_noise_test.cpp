// The IMU's noise model against its configured values: the Allan deviation of a
// resting IMU's output is σ²(τ) = N²/τ + K²·τ/3 for white-noise density N and bias
// random walk K (IEEE Std 952-1997, Annex C; the form Kalibr's imu.yaml values are
// defined by). Measured per axis, gyro and accelerometer, at averaging times where
// each term dominates and where they cross.
#include <cmath>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/robot/imu.h"
#include "trackbed/robot/imu_parts.h"

namespace trackbed::robot {
namespace {

// Allan deviation of `x` (sampled every dt) at averaging time m·dt, from
// non-overlapping clusters: σ² = ½ ⟨(ȳ_{k+1} − ȳ_k)²⟩.
double AllanDeviation(const std::vector<double>& x, std::size_t m) {
  std::vector<double> means;
  for (std::size_t i = 0; i + m <= x.size(); i += m) {
    double sum = 0.0;
    for (std::size_t j = i; j < i + m; ++j) sum += x[j];
    means.push_back(sum / static_cast<double>(m));
  }
  double sum_sq = 0.0;
  for (std::size_t k = 1; k < means.size(); ++k) {
    sum_sq += (means[k] - means[k - 1]) * (means[k] - means[k - 1]);
  }
  return std::sqrt(0.5 * sum_sq / static_cast<double>(means.size() - 1));
}

// One hour at rest (200 Hz, 720 000 samples). The densities are raised above the
// ADIS16448's so that white noise and random walk cross at τ = √3·N/K ≈ 0.17 s and
// both are measurable in an hour: at τ = 20 s the 180 clusters put about 5 % of
// sampling error on the deviation, hence the 15 % tolerance.
TEST(ImuNoiseTest, AllanDeviationFollowsTheConfiguredDensities) {
  ImuOptions o = WithImuPartResolved(ImuOptions{}, Realism::kIdeal);  // no Gauss–Markov terms
  o.rate_hz = 200.0;
  o.gyro_noise_density = 1e-3;
  o.gyro_bias_random_walk = 1e-2;
  o.accel_noise_density = 2e-3;
  o.accel_bias_random_walk = 2e-2;
  o.gyro_initial_bias_std = 0.0;
  o.accel_initial_bias_std = 0.0;
  Imu imu(o, 9.81, 7);
  const std::size_t n = 720000;
  std::vector<std::vector<double>> gyro(3, std::vector<double>(n)),
      accel(3, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const ImuSample s = imu.Sample(static_cast<double>(i) / o.rate_hz, Eigen::Matrix3d::Identity(),
                                   Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    for (int a = 0; a < 3; ++a) {
      gyro[a][i] = s.gyro_radps[a];
      accel[a][i] = s.accel_mps2[a];
    }
  }
  const double dt = 1.0 / o.rate_hz;
  for (const std::size_t m : {2, 10, 40, 200, 1000, 4000}) {
    const double tau = m * dt;
    const auto expected = [tau](double N, double K) {
      return std::sqrt(N * N / tau + K * K * tau / 3.0);
    };
    for (int a = 0; a < 3; ++a) {
      const double g = expected(*o.gyro_noise_density, *o.gyro_bias_random_walk);
      const double f = expected(*o.accel_noise_density, *o.accel_bias_random_walk);
      EXPECT_NEAR(AllanDeviation(gyro[a], m) / g, 1.0, 0.15) << "gyro axis " << a << " tau " << tau;
      EXPECT_NEAR(AllanDeviation(accel[a], m) / f, 1.0, 0.15)
          << "accel axis " << a << " tau " << tau;
    }
  }
}

}  // namespace
}  // namespace trackbed::robot
