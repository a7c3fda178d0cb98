// Calibration of the skid-steer ICR expansion factor χ (Martinez et al. 2005,
// Mandow et al. 2007): the yaw rate the encoders imply with the nominal gauge,
// r(ω_r − ω_l)/B, equals χ times the true yaw rate. Equivalently, with y_L and
// y_R the lateral coordinates of the two tracks' instantaneous centres of
// rotation, χ = (y_L − y_R)/B. On a run with a reference yaw rate (a gyro, a
// motion-capture system, or the simulator's ground truth) χ is an instrumental-
// variable slope through the origin on one-second windows, with its standard error
// and whether the run identifies it (docs/physics.md, "ICR calibration"); B_eff = χ·B.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace trackbed::estimation {

/// One sample of a calibration run; a run's samples are consecutive, at one rate.
struct IcrSample {
  double encoder_yaw_rate_radps = 0.0;    ///< r (ω_r − ω_l) / B, nominal gauge.
  double reference_yaw_rate_radps = 0.0;  ///< True (or gyro) yaw rate.
};

/// What a run must show for its χ to count as identified (docs/physics.md, "ICR
/// calibration").
struct IcrIdentification {
  /// Windows used, at least (10 s of turning at 1 s a window).
  static constexpr int kMinWindows = 10;
  /// RMS of the encoder yaw rate over the windows used, at least [rad/s] (11.5°/s):
  /// the span of turning the fit needs. The calibration runs turn at 0.6 rad/s RMS;
  /// a path follower's or a repeater's gentle steering stays below it.
  static constexpr double kMinTurnRmsRadps = 0.2;
  /// The fit's standard error, at most.
  static constexpr double kMaxStderr = 0.02;
};

struct IcrFit {
  double chi = 1.0;                 ///< Expansion factor, B_eff / B (1 when no window qualifies).
  int samples_used = 0;             ///< Samples in the windows used.
  int windows_used = 0;             ///< Windows whose mean encoder yaw rate exceeds the threshold.
  double rms_residual_radps = 0.0;  ///< RMS over those windows of y − χ·x (window means).
  /// Standard error of χ: delete-a-group jackknife over 20–40 groups of consecutive
  /// windows (one a window below 40 windows; RunningIcrFit); NaN with fewer than two windows (or
  /// none fitted).
  double chi_stderr = std::numeric_limits<double>::quiet_NaN();
  double turn_rms_radps = 0.0;  ///< RMS of the windows' mean encoder yaw rate.
  /// The rules of IcrIdentification hold.
  bool identified = false;
  /// Why not identified ("" when it is), e.g. "turning too gentle: RMS encoder yaw
  /// rate 0.108 rad/s < 0.20 rad/s"; "not fitted" where nothing was (kinematic runs).
  std::string reason = "not fitted";
};

/// χ on windows of `window_samples` consecutive samples (1 s at the encoders' 100 Hz):
/// with y and x a window's mean encoder and reference yaw rate — its heading changes
/// over its length — χ = Σ y² / Σ y·x over the windows with |y| ≥
/// `min_yaw_rate_radps`: an instrumental-variable slope, y instrumenting x. Noise in
/// the reference (yaw the terrain causes, which the tracks did not command) enters
/// only the denominator's sum, where it averages out, instead of pulling χ toward zero
/// as a least-squares slope on the reference does; the encoders' own noise is the
/// window's last tick, since counts telescope. The windows also average out steering
/// faster than the body follows (a repeater's left–right corrections several times a
/// second). Throws std::invalid_argument when `window_samples` < 1.
IcrFit FitIcrExpansion(const std::vector<IcrSample>& samples, int window_samples = 100,
                       double min_yaw_rate_radps = 0.05);

/// FitIcrExpansion sample by sample, in bounded memory (a run of hours): the sums of
/// the windows used, and for the standard error the sums of at most 40 groups of
/// consecutive windows (pairs of groups merge when a run fills them, so a long run
/// keeps 20–40 groups of equal length but the last).
class RunningIcrFit {
 public:
  /// Throws std::invalid_argument when `window_samples` < 1.
  explicit RunningIcrFit(int window_samples = 100, double min_yaw_rate_radps = 0.05);
  void Add(const IcrSample& s);
  IcrFit Fit() const;
  /// The jackknife's groups held (at most 40 however long the run).
  std::size_t groups() const { return groups_.size(); }

 private:
  struct Sums {
    double yy = 0.0, yx = 0.0, xx = 0.0;
    int windows = 0;
    void Add(const Sums& o);
  };
  double JackknifeStderr() const;

  int window_samples_;
  double min_yaw_rate_radps_;
  double window_y_ = 0.0, window_x_ = 0.0;  // the open window's means so far
  int in_window_ = 0;
  Sums total_;
  std::vector<Sums> groups_;
  int windows_per_group_ = 1;
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
