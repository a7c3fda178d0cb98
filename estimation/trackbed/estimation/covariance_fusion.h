// A second fusion method beside Ham et al.'s fuzzy weight: per camera interval, the
// gyro-led, slip-aware wheel odometry's planar increment is the prediction and visual
// odometry's planar increment a measurement of the same motion, each with its
// covariance; the fused increment is their minimum-variance combination,
//   ΔX = ΔX_WO + K·(ΔX_VO − ΔX_WO),  K = Q·(Q + R)⁻¹,
// Q the prediction's covariance (the wheels' speed σ over the interval, the gyro's
// rotation variance), R VO's own (docs/localization.md, "Covariance"). A VO increment
// whose Mahalanobis distance from the prediction lies beyond the gate's χ² quantile is
// left out, so that one poor input cannot pull the estimate away.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "trackbed/common/pose2.h"

namespace trackbed::estimation {

/// The quantile of χ² with `dof` degrees of freedom (1 or 3) at `probability` in (0, 1).
double ChiSquareQuantile(int dof, double probability);

/// The minimum-variance combination of two estimates of one planar increment (x, y, yaw
/// in the previous pose's frame), or `prediction` unchanged when the measurement lies
/// beyond `gate` (a squared Mahalanobis distance); `used` (may be null) says which.
geometry::Pose2 CombineIncrements(const geometry::Pose2& prediction, const Eigen::Matrix3d& Q,
                                  const geometry::Pose2& measurement, const Eigen::Matrix3d& R,
                                  double gate, bool* used = nullptr);

/// The covariance of the planar pose `pose` ⊕ `increment` (geometry::Compose) to first
/// order, from the pose's covariance `P` and the increment's `C`, independent: F·P·Fᵀ +
/// G·C·Gᵀ with F, G the composition's Jacobians in the pose and in the increment [m²,
/// m·rad, rad² for x, y, yaw].
Eigen::Matrix3d ComposeCovariance(const geometry::Pose2& pose, const Eigen::Matrix3d& P,
                                  const geometry::Pose2& increment, const Eigen::Matrix3d& C);

/// Composes the fused increments into a planar pose, and their covariances into the
/// pose's: the fused increment's is (I − K)·Q where VO's was used, Q where not.
class CovarianceFusion {
 public:
  CovarianceFusion(const geometry::Pose2& initial_pose, double gate)
      : pose_(initial_pose), gate_(gate) {}

  /// One camera interval: the prediction and its covariance Q, and VO's increment and
  /// covariance R when VO has a motion with a covariance. True when VO's was used.
  bool Add(const geometry::Pose2& prediction, const Eigen::Matrix3d& Q,
           const std::optional<geometry::Pose2>& measurement, const Eigen::Matrix3d& R);

  const geometry::Pose2& pose() const { return pose_; }
  /// The covariance of pose() (x, y, yaw) [m², m·rad, rad²], zero at the initial pose.
  const Eigen::Matrix3d& covariance() const { return covariance_; }

 private:
  geometry::Pose2 pose_;
  Eigen::Matrix3d covariance_ = Eigen::Matrix3d::Zero();
  double gate_;
};

}  // namespace trackbed::estimation
