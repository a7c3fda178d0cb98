// How uncertain each estimator says its planar pose is, and when that uncertainty
// passes a stated bound: the estimate then counts as lost ("localization lost",
// docs/localization.md "Each estimator's covariance"). An estimator that carries no covariance of
// its own reports none, rather than one made up for it.
#pragma once

#include <optional>

#include <Eigen/Core>

namespace trackbed::estimation {

/// The bound beyond which a pose estimate counts as lost. The defaults are navigation's
/// success tolerance (0.1 m and 2°, navigation::SuccessCriteria): an estimate less
/// certain than that cannot tell whether the robot stands at its goal.
struct LocalizationLostOptions {
  /// Largest horizontal position uncertainty [m], > 0: `sigmas` standard deviations along
  /// the covariance's worst direction.
  double position_m = 0.1;
  /// Largest heading uncertainty [°], in (0, 180]: `sigmas` standard deviations.
  double heading_deg = 2.0;
  /// Standard deviations the uncertainty is counted in, > 0 (2: about the 95 % interval
  /// of one coordinate).
  double sigmas = 2.0;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (`estimation.localization_lost`,
  /// docs/scenario_format.md), read and written by the config archive
  /// (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("position_m", &position_m);
    a->Visit("heading_deg", &heading_deg);
    a->Visit("sigmas", &sigmas);
  }
};

/// The size of a planar pose covariance (x, y, yaw).
struct PoseUncertainty {
  /// Standard deviation of the horizontal position along its worst direction (the
  /// square root of the position block's largest eigenvalue) [m]; +∞ when the
  /// covariance is not finite.
  double position_sigma_m = 0.0;
  /// Standard deviation of the heading [rad]; +∞ when not finite.
  double heading_sigma_rad = 0.0;
};

/// The size of `P` (x, y, yaw) [m², m·rad, rad²].
PoseUncertainty UncertaintyOf(const Eigen::Matrix3d& P);

/// Whether `u` lies beyond the bound: `sigmas`·σ above position_m or heading_deg.
bool BeyondBound(const PoseUncertainty& u, const LocalizationLostOptions& bound);

/// Each estimator's planar pose covariance now (x, y, yaw) [m², m·rad, rad²], where it
/// has one of its own: none for wheel odometry (the encoders measure no slip they miss)
/// and Ham et al.'s fusion (a weight, not a variance).
struct PoseCovariances {
  /// Visual odometry's frames' covariances composed; +∞ after a frame without a motion
  /// (VO alone then knows nothing of that interval) or without a covariance.
  std::optional<Eigen::Matrix3d> visual_odometry;
  /// The covariance fusion's (FusionOptions::Method::kCovariance), at the last frame.
  std::optional<Eigen::Matrix3d> fused;
  /// The EKF's pose block.
  std::optional<Eigen::Matrix3d> ekf;
};

}  // namespace trackbed::estimation
