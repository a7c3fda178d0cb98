// The overlapping Allan deviation of a rate sequence (a gyro's or an accelerometer's
// output at rest), as IEEE Std 952-1997 (Annex C) defines the Allan variance and NIST
// SP 1065 (Riley 2008, eq. 12) its overlapping estimator: from the integrated sequence
// θ (θ_0 = 0, θ_{k+1} = θ_k + x_k·dt),
//   σ²(τ) = Σ_{k=0}^{N−2m} (θ_{k+2m} − 2θ_{k+m} + θ_k)² / (2τ²(N − 2m + 1)),  τ = m·dt.
// For a real IMU's log as well as the simulated one's (bench/imu_heading_drift).
#pragma once

#include <cstddef>
#include <vector>

namespace trackbed::estimation {

/// The overlapping Allan deviation of `rate` (sampled every `dt_s`) at each averaging
/// time of `taus_s` (rounded to a whole number m >= 1 of samples). Throws
/// std::invalid_argument when dt_s <= 0 or an averaging time leaves fewer than 2m + 1
/// samples.
std::vector<double> OverlappingAllanDeviation(const std::vector<double>& rate, double dt_s,
                                              const std::vector<double>& taus_s);

/// The same from the integral itself, `theta` (the angle or velocity, its first value
/// the start) sampled every `dt_s`: a long record's integral kept at a coarser step than
/// the rate's serves every averaging time that is a multiple of that step.
std::vector<double> OverlappingAllanDeviationOfIntegral(const std::vector<double>& theta,
                                                        double dt_s,
                                                        const std::vector<double>& taus_s);

}  // namespace trackbed::estimation
