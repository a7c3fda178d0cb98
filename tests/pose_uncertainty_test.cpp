// Each estimator's own pose covariance and the localization-lost bound
// (estimation/pose_uncertainty.h, estimation/covariance_fusion.h): the covariance
// composed along a path by its first-order rule, exact on constructed increments, and
// the bound's test on exact values.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "trackbed/common/option_error.h"
#include "trackbed/estimation/covariance_fusion.h"
#include "trackbed/estimation/pose_uncertainty.h"

namespace trackbed::estimation {
namespace {

TEST(PoseUncertaintyTest, StraightIncrementsComposeTheirCovariancesExactly) {
  // Two steps of 1 m straight ahead, each with variances a, b, c on (x, y, yaw): the
  // second step's heading error swings the first metre's end sideways by 1 m per rad.
  const double a = 1e-4, b = 4e-4, c = 9e-6;
  const Eigen::Matrix3d C = Eigen::Vector3d(a, b, c).asDiagonal();
  const geometry::Pose2 step{1.0, 0.0, 0.0};
  Eigen::Matrix3d P = ComposeCovariance({0.0, 0.0, 0.0}, Eigen::Matrix3d::Zero(), step, C);
  EXPECT_TRUE(P.isApprox(C));
  P = ComposeCovariance({1.0, 0.0, 0.0}, P, step, C);
  EXPECT_NEAR(P(0, 0), 2 * a, 1e-15);
  EXPECT_NEAR(P(1, 1), 2 * b + c, 1e-15);
  EXPECT_NEAR(P(1, 2), c, 1e-15);
  EXPECT_NEAR(P(2, 2), 2 * c, 1e-15);
  EXPECT_NEAR(P(0, 1), 0.0, 1e-15);
  // Facing +y, the same step's forward variance lies along y.
  const Eigen::Matrix3d Py =
      ComposeCovariance({0.0, 0.0, M_PI / 2}, Eigen::Matrix3d::Zero(), step, C);
  EXPECT_NEAR(Py(1, 1), a, 1e-15);
  EXPECT_NEAR(Py(0, 0), b, 1e-15);
}

TEST(PoseUncertaintyTest, TheCovarianceFusionsPoseCovarianceShrinksWithEachMeasurementUsed) {
  const Eigen::Matrix3d Q = Eigen::Vector3d(1e-6, 4e-6, 1e-7).asDiagonal();
  const geometry::Pose2 step{0.04, 0.0, 0.0};
  CovarianceFusion predicted({0.0, 0.0, 0.0}, 100.0), measured({0.0, 0.0, 0.0}, 100.0);
  EXPECT_TRUE(predicted.covariance().isZero());
  predicted.Add(step, Q, std::nullopt, Eigen::Matrix3d::Zero());
  EXPECT_TRUE(measured.Add(step, Q, step, Q));
  // Alone the prediction's covariance; with an equally good measurement half of it.
  EXPECT_TRUE(predicted.covariance().isApprox(Q));
  EXPECT_TRUE(measured.covariance().isApprox(0.5 * Q));
  // A measurement beyond the gate is left out: the prediction's covariance is added.
  CovarianceFusion gated({0.0, 0.0, 0.0}, 1.0);
  EXPECT_FALSE(gated.Add(step, Q, geometry::Pose2{1.0, 0.0, 0.0}, Q));
  EXPECT_TRUE(gated.covariance().isApprox(Q));
}

TEST(PoseUncertaintyTest, TheBoundCountsSigmasAlongTheWorstDirection) {
  // Position block with eigenvalues 0.0025 and 0.0004 (σ 0.05 and 0.02 m), rotated 30°.
  // The bound is 0.101 m and 2°, so 2σ lies clearly inside it.
  const double t = M_PI / 6, c = std::cos(t), s = std::sin(t);
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  P.topLeftCorner<2, 2>() = R * Eigen::Vector2d(0.0025, 0.0004).asDiagonal() * R.transpose();
  P(2, 2) = std::pow(0.5 * M_PI / 180.0, 2);  // σ 0.5°
  const PoseUncertainty u = UncertaintyOf(P);
  EXPECT_NEAR(u.position_sigma_m, 0.05, 1e-12);
  EXPECT_NEAR(u.heading_sigma_rad, 0.5 * M_PI / 180.0, 1e-15);
  LocalizationLostOptions bound;  // 2σ
  bound.position_m = 0.101;
  EXPECT_FALSE(BeyondBound(u, bound));  // 2 × 0.05 m, 2 × 0.5°: within both
  bound.position_m = 0.099;
  EXPECT_TRUE(BeyondBound(u, bound));
  bound.position_m = 0.101;
  bound.heading_deg = 0.99;  // 2 × 0.5° beyond it
  EXPECT_TRUE(BeyondBound(u, bound));
  // A covariance that is not finite is infinitely uncertain, and beyond any bound.
  const PoseUncertainty lost =
      UncertaintyOf(Eigen::Matrix3d::Constant(std::numeric_limits<double>::infinity()));
  EXPECT_TRUE(std::isinf(lost.position_sigma_m));
  EXPECT_TRUE(std::isinf(lost.heading_sigma_rad));
  EXPECT_TRUE(BeyondBound(lost, LocalizationLostOptions{}));
}

TEST(PoseUncertaintyTest, InvalidBoundsAreRefusedByName) {
  LocalizationLostOptions o;
  o.position_m = 0.0;
  EXPECT_THROW(o.Validate(), OptionError);
  o = {};
  o.heading_deg = 181.0;
  EXPECT_THROW(o.Validate(), OptionError);
  o = {};
  o.sigmas = -1.0;
  try {
    o.Validate();
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_NE(std::string(e.what()).find("sigmas"), std::string::npos);
  }
}

}  // namespace
}  // namespace trackbed::estimation
