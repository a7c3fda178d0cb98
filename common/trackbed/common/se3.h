// Small rigid-motion helpers (Sophus-like vocabulary over Eigen types): the
// cross-product matrix, the SO(3) exponential of a rotation vector, a rotation's
// angle, and the decoupled left increment the Gauss–Newton solvers step with.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace trackbed::geometry {

/// [v]×, the matrix with [v]× w = v × w.
inline Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

/// exp([φ]×): the rotation by |φ| about φ/|φ| (the identity for φ = 0).
inline Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  return angle > 0.0 ? Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix()
                     : Eigen::Matrix3d::Identity();
}

/// The angle of rotation R [rad], in [0, π].
inline double RotationAngle(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle(); }

/// T stepped by the decoupled left increment (δt, φ): R ← exp([φ]×) R and
/// t ← exp([φ]×) t + δt.
inline Eigen::Isometry3d ApplyLeftIncrement(const Eigen::Vector3d& dt, const Eigen::Vector3d& phi,
                                            const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d dR = ExpSO3(phi);
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = dR * T.linear();
  out.translation() = dR * T.translation() + dt;
  return out;
}

}  // namespace trackbed::geometry
