// Pose uncertainty and the localization-lost bound (see pose_uncertainty.h).
#include "trackbed/estimation/pose_uncertainty.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "trackbed/common/option_error.h"
#include "trackbed/common/units.h"

namespace trackbed::estimation {

void LocalizationLostOptions::Validate() const {
  option_check::Positive("position_m", position_m);
  option_check::Positive("heading_deg", heading_deg);
  option_check::InRange("heading_deg", heading_deg, 0.0, 180.0);
  option_check::Positive("sigmas", sigmas);
}

PoseUncertainty UncertaintyOf(const Eigen::Matrix3d& P) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!P.allFinite()) return {kInf, kInf};
  const Eigen::Matrix2d position = P.topLeftCorner<2, 2>();
  const double largest =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(position, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .maxCoeff();
  return {std::sqrt(std::max(largest, 0.0)), std::sqrt(std::max(P(2, 2), 0.0))};
}

bool BeyondBound(const PoseUncertainty& u, const LocalizationLostOptions& bound) {
  return bound.sigmas * u.position_sigma_m > bound.position_m ||
         bound.sigmas * u.heading_sigma_rad > units::Radians(bound.heading_deg);
}

}  // namespace trackbed::estimation
