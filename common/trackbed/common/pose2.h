// Planar poses and motions (x, y, heading) and their composition: the
// odometry of a ground robot lives in the plane (Ham et al. 2012, eq. 6).
#pragma once

#include <cmath>

#include <Eigen/Geometry>

namespace trackbed::geometry {

/// A pose in the plane: position [m] and heading [rad], or a motion
/// expressed in the frame it starts from (dx forward, dy left, dyaw).
struct Pose2 {
  double x = 0.0, y = 0.0, yaw = 0.0;
};

/// Wraps an angle to (−π, π].
inline double WrapAngle(double a) { return std::remainder(a, 2.0 * M_PI); }

/// a ⊕ b: the pose reached by moving by `b` (expressed in `a`'s frame) from `a`.
inline Pose2 Compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.yaw), s = std::sin(a.yaw);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, WrapAngle(a.yaw + b.yaw)};
}

/// a⁻¹ ⊕ b: the motion from `a` to `b`, in `a`'s frame.
inline Pose2 Between(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.yaw), s = std::sin(a.yaw);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, WrapAngle(b.yaw - a.yaw)};
}

/// The planar part of a 3-D pose (heading = yaw of the body x axis).
inline Pose2 PlanarPose(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d& R = T.linear();
  return {T.translation().x(), T.translation().y(), std::atan2(R(1, 0), R(0, 0))};
}

/// A 3-D pose at height `z` with the planar pose's heading, level.
inline Eigen::Isometry3d ToIsometry(const Pose2& p, double z = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.x, p.y, z);
  return T;
}

}  // namespace trackbed::geometry
