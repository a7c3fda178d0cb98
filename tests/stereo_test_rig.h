// The stereo rig and the pose helpers that the stereo motion-estimation tests and the
// visual odometry tests share: a 640×480 pair with a 12 cm baseline, poses from an
// axis-angle vector, and rotation/translation errors between two poses.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "trackbed/common/se3.h"
#include "trackbed/estimation/stereo_motion_estimation.h"

namespace trackbed::estimation::stereo_test {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerRad = 180.0 / kPi;

/// fx = 500, fy = 505 px, principal point at the centre of 640×480, baseline 0.12 m.
inline geometry::StereoCamera TestCamera() {
  geometry::StereoCamera c;
  c.left.width_px = 640;
  c.left.height_px = 480;
  c.left.fx = 500.0;
  c.left.fy = 505.0;
  c.left.cx = 319.5;
  c.left.cy = 239.5;
  c.baseline_m = 0.12;
  return c;
}

/// The pose with rotation Exp(axis_angle) [rad] and translation t [m].
inline Eigen::Isometry3d Pose(const Eigen::Vector3d& axis_angle, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = geometry::ExpSO3(axis_angle);
  T.translation() = t;
  return T;
}

/// Angle of the rotation between A's and B's [deg].
inline double RotationErrorDeg(const Eigen::Isometry3d& A, const Eigen::Isometry3d& B) {
  return Eigen::AngleAxisd(A.linear().transpose() * B.linear()).angle() * kDegPerRad;
}

/// Distance between A's and B's translations [m].
inline double TranslationError(const Eigen::Isometry3d& A, const Eigen::Isometry3d& B) {
  return (A.translation() - B.translation()).norm();
}

}  // namespace trackbed::estimation::stereo_test
