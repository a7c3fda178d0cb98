// A stereo motion's covariance from its inliers' geometry, and a rotation prior added to
// it (see motion_covariance.h).
#include "trackbed/estimation/motion_covariance.h"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>

#include "trackbed/common/se3.h"

namespace trackbed::estimation {
namespace {

/// ∂Triangulate/∂(u_left, v, u_right) at the point p seen with disparity d:
/// Z = fx·b/d, X = (u − cx)·Z/fx, Y = (v − cy)·Z/fy, d = u_left − u_right, so
/// ∂p/∂d = −p/d, ∂p/∂u_left = (Z/fx, 0, 0) + ∂p/∂d, ∂p/∂v = (0, Z/fy, 0), ∂p/∂u_right = p/d.
Eigen::Matrix3d TriangulationJacobian(const geometry::StereoCamera& camera,
                                      const Eigen::Vector3d& p, double d) {
  Eigen::Matrix3d J;
  const Eigen::Vector3d dp_dd = -p / d;
  J.col(0) = Eigen::Vector3d(p.z() / camera.left.fx, 0.0, 0.0) + dp_dd;
  J.col(1) = Eigen::Vector3d(0.0, p.z() / camera.left.fy, 0.0);
  J.col(2) = -dp_dd;
  return J;
}

}  // namespace

MotionCovariance EstimateMotionCovariance(const std::vector<MotionCorrespondence>& correspondences,
                                          const std::vector<unsigned char>& mask,
                                          const geometry::StereoCamera& camera,
                                          const Eigen::Isometry3d& T_curr_prev, double huber_px,
                                          double disparity_offset_std_px) {
  if (!mask.empty() && mask.size() != correspondences.size()) {
    throw std::invalid_argument("EstimateMotionCovariance: mask has " +
                                std::to_string(mask.size()) + " entries for " +
                                std::to_string(correspondences.size()) + " correspondences");
  }
  MotionCovariance out;
  // The refinement's normal matrix, Σ w·JᵀJ, and the covariance of its gradient per
  // unit image variance, Σ w²·JᵀSJ.
  MotionCovarianceMatrix normal = MotionCovarianceMatrix::Zero();
  MotionCovarianceMatrix gradient_cov = MotionCovarianceMatrix::Zero();
  Eigen::Matrix<double, 6, 1> offset_gradient = Eigen::Matrix<double, 6, 1>::Zero();
  double weighted_sq = 0.0;
  Eigen::Matrix<double, 3, 6> J;
  const Eigen::Matrix3d& R = T_curr_prev.linear();
  for (std::size_t i = 0; i < correspondences.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    const MotionCorrespondence& c = correspondences[i];
    const double d_prev = c.z_prev.x() - c.z_prev.z();
    if (!(d_prev > 0.0) || !(c.p_prev.z() > 0.0)) continue;
    if (!((T_curr_prev * c.p_prev).z() > 1e-6)) continue;
    const Eigen::Vector3d r = StereoReprojectionResidual(camera, T_curr_prev, c, &J);
    // ∂Project/∂p is the Jacobian's translation block (∂p/∂ρ = I).
    const Eigen::Matrix3d A = J.leftCols<3>() * R * TriangulationJacobian(camera, c.p_prev, d_prev);
    const Eigen::Matrix3d S = Eigen::Matrix3d::Identity() + A * A.transpose();
    const double e = r.norm();
    const bool linear = huber_px > 0.0 && e > huber_px;
    const double w = linear ? huber_px / e : 1.0;
    // The Huber cost's Hessian in r: I inside, (k/e)·(I − r̂r̂ᵀ) beyond (no curvature
    // along the residual where the cost grows linearly).
    Eigen::Matrix3d hessian = Eigen::Matrix3d::Identity();
    if (linear) {
      const Eigen::Vector3d u = r / e;
      normal.noalias() += w * J.transpose() * (Eigen::Matrix3d::Identity() - u * u.transpose()) * J;
      hessian = w * (Eigen::Matrix3d::Identity() - u * u.transpose());
    } else {
      normal.noalias() += J.transpose() * J;
    }
    // ∂r/∂δ: the offset shifts the right column of both observations.
    const Eigen::Vector3d b = Eigen::Vector3d::UnitZ() - A.col(2);
    offset_gradient.noalias() += J.transpose() * (hessian * b);
    gradient_cov.noalias() += (w * w) * J.transpose() * S * J;
    weighted_sq += r.dot(S.llt().solve(r));
    ++out.points;
  }
  const int dof = 3 * out.points - 6;
  if (out.points < 3 || dof <= 0) return out;
  const Eigen::LDLT<MotionCovarianceMatrix> ldlt(normal);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
      !(ldlt.vectorD().minCoeff() > 1e-12 * ldlt.vectorD().maxCoeff())) {
    return out;
  }
  const double sigma2 = weighted_sq / static_cast<double>(dof);
  const MotionCovarianceMatrix normal_inv = ldlt.solve(MotionCovarianceMatrix::Identity());
  MotionCovarianceMatrix unit = normal_inv * gradient_cov * normal_inv;
  unit = 0.5 * (unit + unit.transpose()).eval();
  if (disparity_offset_std_px > 0.0 && sigma2 > 0.0) {
    // The shared offset as a consider parameter (file comment of the header).
    const Eigen::Matrix<double, 6, 1> g = normal_inv * offset_gradient;
    const double ratio = disparity_offset_std_px * disparity_offset_std_px / sigma2;
    unit.noalias() += ratio * g * g.transpose();
  }
  out.image_noise_px = std::sqrt(sigma2);
  out.unit_information = unit.ldlt().solve(MotionCovarianceMatrix::Identity());
  out.covariance = sigma2 * unit;
  out.valid = out.covariance.allFinite() && out.unit_information.allFinite();
  return out;
}

void AddRotationPrior(const RotationPrior& prior, MotionCovariance* vo,
                      Eigen::Isometry3d* T_curr_prev) {
  if (!vo->valid) throw std::invalid_argument("AddRotationPrior: the motion has no covariance");
  if (!(prior.std_rad > 0.0)) throw std::invalid_argument("AddRotationPrior: std_rad <= 0");
  // e_R(φ) = Log(Exp(φ)·R_curr_prev·R_prev_curr_prior) ≈ e_R + φ for small disagreements.
  const Eigen::AngleAxisd disagreement(T_curr_prev->linear() * prior.R_prev_curr);
  const Eigen::Vector3d e_R = disagreement.angle() * disagreement.axis();
  const double w = 1.0 / (prior.std_rad * prior.std_rad);
  const Eigen::LDLT<MotionCovarianceMatrix> vo_ldlt(vo->covariance);
  MotionCovarianceMatrix information = vo_ldlt.solve(MotionCovarianceMatrix::Identity());
  information.bottomRightCorner<3, 3>().diagonal().array() += w;
  Eigen::Matrix<double, 6, 1> gradient = Eigen::Matrix<double, 6, 1>::Zero();
  gradient.tail<3>() = w * e_R;
  const Eigen::LDLT<MotionCovarianceMatrix> ldlt(information);
  const MotionIncrement delta = -ldlt.solve(gradient);
  *T_curr_prev = ApplyIncrement(delta, *T_curr_prev);
  vo->covariance = ldlt.solve(MotionCovarianceMatrix::Identity());
  vo->covariance = 0.5 * (vo->covariance + vo->covariance.transpose()).eval();
  vo->unit_information = information * (vo->image_noise_px * vo->image_noise_px);
}

MotionCovarianceMatrix TransformMotionCovariance(const MotionCovarianceMatrix& covariance,
                                                 const Eigen::Isometry3d& T_ba) {
  const Eigen::Matrix3d& R = T_ba.linear();
  MotionCovarianceMatrix Ad = MotionCovarianceMatrix::Zero();
  Ad.topLeftCorner<3, 3>() = R;
  Ad.topRightCorner<3, 3>() = geometry::Skew(T_ba.translation()) * R;
  Ad.bottomRightCorner<3, 3>() = R;
  return Ad * covariance * Ad.transpose();
}

}  // namespace trackbed::estimation
