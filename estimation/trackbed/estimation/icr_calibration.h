// Calibration of the skid-steer ICR expansion factor χ (Martinez et al. 2005,
// Mandow et al. 2007): the yaw rate the encoders imply with the nominal gauge,
// r(ω_r − ω_l)/B, equals χ times the true yaw rate. Equivalently, with y_L and
// y_R the lateral coordinates of the two tracks' instantaneous centres of
// rotation, χ = (y_L − y_R)/B. On a calibration run with a reference yaw rate
// (a gyro, a motion-capture system, or the simulator's ground truth) χ is the
// least-squares slope through the origin; B_eff = χ·B.
#pragma once

#include <vector>

namespace trackbed::estimation {

/// One sample of a calibration run.
struct IcrSample {
  double encoder_yaw_rate_radps = 0.0;    ///< r (ω_r − ω_l) / B, nominal gauge.
  double reference_yaw_rate_radps = 0.0;  ///< True (or gyro) yaw rate.
};

struct IcrFit {
  double chi = 1.0;      ///< Expansion factor, B_eff / B.
  int samples_used = 0;  ///< Samples with |reference| above the threshold.
  double rms_residual_radps = 0.0;
};

/// Least-squares χ over samples whose reference yaw rate exceeds
/// `min_yaw_rate_radps` in magnitude. Returns samples_used = 0 (and χ = 1)
/// when there are none.
IcrFit FitIcrExpansion(const std::vector<IcrSample>& samples, double min_yaw_rate_radps = 0.05);

/// FitIcrExpansion accumulated sample by sample, in constant memory (a run of hours):
/// χ and samples_used bit for bit the same (the same sums in the same order); the RMS
/// residual from Σy² − χ·Σxy, equal up to rounding (the last digits move).
class RunningIcrFit {
 public:
  explicit RunningIcrFit(double min_yaw_rate_radps = 0.05)
      : min_yaw_rate_radps_(min_yaw_rate_radps) {}
  void Add(const IcrSample& s);
  IcrFit Fit() const;

 private:
  double min_yaw_rate_radps_;
  double sxy_ = 0.0, sxx_ = 0.0, syy_ = 0.0;
  int used_ = 0;
};

/// χ of a skid-steer vehicle turning in place in the rigid-plastic limit: equal
/// point loads at body x positions `station_x_m` on each side, half track c =
/// `half_track_m`, isotropic Coulomb friction. Each side's ICR lies e = y_ICR − c
/// outside it, where the yaw moment of the friction forces vanishes:
///   Σ_i (c·e − x_i²) / √(e² + x_i²) = 0,
/// and χ = (c + e)/c (derivation in docs/physics.md). Two stations at ±a give
/// the closed form 1 + (a/c)². Throws std::invalid_argument when no station is
/// off the axle (x_i all zero) or c <= 0.
double RigidPlasticIcrExpansion(const std::vector<double>& station_x_m, double half_track_m);

}  // namespace trackbed::estimation
