// The covariance fusion (see covariance_fusion.h).
#include "trackbed/estimation/covariance_fusion.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/LU>

namespace trackbed::estimation {
namespace {

// P(χ² <= x) for 1 and 3 degrees of freedom, in closed form.
double ChiSquareCdf(int dof, double x) {
  const double a = std::erf(std::sqrt(x / 2.0));
  if (dof == 1) return a;
  return a - std::sqrt(2.0 * x / M_PI) * std::exp(-x / 2.0);
}

}  // namespace

double ChiSquareQuantile(int dof, double probability) {
  if (dof != 1 && dof != 3) throw std::invalid_argument("ChiSquareQuantile: dof must be 1 or 3");
  if (!(probability > 0.0 && probability < 1.0)) {
    throw std::invalid_argument("ChiSquareQuantile: probability must be in (0, 1)");
  }
  double lo = 0.0, hi = 1.0;
  while (ChiSquareCdf(dof, hi) < probability) hi *= 2.0;
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (ChiSquareCdf(dof, mid) < probability ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

geometry::Pose2 CombineIncrements(const geometry::Pose2& prediction, const Eigen::Matrix3d& Q,
                                  const geometry::Pose2& measurement, const Eigen::Matrix3d& R,
                                  double gate, bool* used) {
  Eigen::Vector3d nu(measurement.x - prediction.x, measurement.y - prediction.y,
                     geometry::WrapAngle(measurement.yaw - prediction.yaw));
  const Eigen::Matrix3d S_inv = (Q + R).inverse();
  const bool inside = S_inv.allFinite() && nu.dot(S_inv * nu) <= gate;
  if (used) *used = inside;
  if (!inside) return prediction;
  const Eigen::Vector3d d = Q * S_inv * nu;
  return {prediction.x + d(0), prediction.y + d(1), geometry::WrapAngle(prediction.yaw + d(2))};
}

Eigen::Matrix3d ComposeCovariance(const geometry::Pose2& pose, const Eigen::Matrix3d& P,
                                  const geometry::Pose2& increment, const Eigen::Matrix3d& C) {
  const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(0, 2) = -s * increment.x - c * increment.y;
  F(1, 2) = c * increment.x - s * increment.y;
  Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
  G.topLeftCorner<2, 2>() << c, -s, s, c;
  return F * P * F.transpose() + G * C * G.transpose();
}

bool CovarianceFusion::Add(const geometry::Pose2& prediction, const Eigen::Matrix3d& Q,
                           const std::optional<geometry::Pose2>& measurement,
                           const Eigen::Matrix3d& R) {
  bool used = false;
  const geometry::Pose2 increment =
      measurement ? CombineIncrements(prediction, Q, *measurement, R, gate_, &used) : prediction;
  // The fused increment's covariance: (I − K)·Q, K = Q·(Q + R)⁻¹, where VO's was used.
  const Eigen::Matrix3d C = used ? Eigen::Matrix3d(Q - Q * (Q + R).inverse() * Q) : Q;
  covariance_ = ComposeCovariance(pose_, covariance_, increment, 0.5 * (C + C.transpose()));
  pose_ = geometry::Compose(pose_, increment);
  return used;
}

}  // namespace trackbed::estimation
