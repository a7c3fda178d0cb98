// The covariance of a stereo motion from its inliers' geometry (motion_covariance.h) on
// constructed scenes with a known motion and Gaussian pixel noise: the covariance is
// consistent with the refined motion's error against the truth (the average normalised
// estimation error squared over the trials inside its two-sided 95 % χ² interval), on
// well-spread points and on a frontal wall (optimistic where disparities are below a
// pixel or two: far points only); far points give a
// translation far less certain than well-spread ones; a wall ties the sideways
// translation to the yaw; a gyro's rotation as a prior shrinks the sideways error by
// ground truth; and the covariance's change of frame against the exact increment.
#include "trackbed/estimation/motion_covariance.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "stereo_test_rig.h"
#include "trackbed/common/random.h"
#include "trackbed/estimation/stereo_motion_estimation.h"

namespace trackbed::estimation {
namespace {

using stereo_test::Pose;
using stereo_test::TestCamera;

constexpr double kSigmaPx = 0.3;
constexpr int kTrials = 200;
// The two-sided 95 % interval of the mean of kTrials χ²(6) draws: χ²(1200) quantiles
// 1106.0 and 1297.8 (Wilson–Hilferty) over 200.
constexpr double kMeanNeesLow = 5.530, kMeanNeesHigh = 6.489;

/// A point in the left camera generated from a pixel and a depth.
using PointSource = std::function<Eigen::Vector3d(random::Generator&)>;

/// Points seen at pixels uniform over the image, at depths uniform in [z0, z1] m.
PointSource Spread(double z0, double z1) {
  return [z0, z1](random::Generator& rng) {
    const geometry::StereoCamera c = TestCamera();
    const double Z = rng.Uniform(z0, z1);
    return Eigen::Vector3d((rng.Uniform(40.0, 600.0) - c.left.cx) * Z / c.left.fx,
                           (rng.Uniform(40.0, 440.0) - c.left.cy) * Z / c.left.fy, Z);
  };
}

/// `n` correspondences of points from `source` moved by `truth`, every pixel coordinate
/// with Gaussian noise of kSigmaPx, both points triangulated from the noisy pixels; the
/// right image's columns shifted by `offset_px` in both frames (a rig's disparity
/// offset, which every point shares).
std::vector<MotionCorrespondence> Measure(const Eigen::Isometry3d& truth, int n,
                                          const PointSource& source, random::Generator& rng,
                                          double offset_px = 0.0) {
  const geometry::StereoCamera c = TestCamera();
  const auto measure = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d e(rng.Gaussian(), rng.Gaussian(), rng.Gaussian());
    return Eigen::Vector3d(c.Project(p) + kSigmaPx * e + Eigen::Vector3d(0.0, 0.0, offset_px));
  };
  std::vector<MotionCorrespondence> out;
  while (static_cast<int>(out.size()) < n) {
    const Eigen::Vector3d p = source(rng);
    const Eigen::Vector3d q = truth * p;
    const Eigen::Vector3d z0 = measure(p), z1 = measure(q);
    if (!(q.z() > 1.0) || z1.x() < 0.0 || z1.x() > 639.0 || z1.y() < 0.0 || z1.y() > 479.0 ||
        !(z0.x() - z0.z() > 0.0) || !(z1.x() - z1.z() > 0.0)) {
      continue;
    }
    MotionCorrespondence m;
    m.p_prev = c.Triangulate(z0.x(), z0.y(), z0.x() - z0.z());
    m.p_curr = c.Triangulate(z1.x(), z1.y(), z1.x() - z1.z());
    m.z_prev = z0;
    m.z_curr = z1;
    out.push_back(m);
  }
  return out;
}

/// The left increment ε with truth = ApplyIncrement(ε, estimate).
Eigen::Matrix<double, 6, 1> ErrorOf(const Eigen::Isometry3d& truth,
                                    const Eigen::Isometry3d& estimate) {
  const Eigen::Isometry3d E = truth * estimate.inverse();
  const Eigen::AngleAxisd aa(E.linear());
  Eigen::Matrix<double, 6, 1> e;
  e << E.translation(), aa.angle() * aa.axis();
  return e;
}

/// The forward motion of a robot's camera over 0.1 s at 1 m/s, turning at 10 °/s.
Eigen::Isometry3d FrameMotion() {
  return Pose(Eigen::Vector3d(0.0, 0.0175, 0.0), Eigen::Vector3d(0.004, 0.001, -0.1));
}

struct TrialStats {
  double mean_nees = 0.0;
  double mean_translation_std_m = 0.0;  ///< √(trace of the translation block / 3)
  double rms_error_x_m = 0.0;           ///< sideways (camera x) error against the truth
  double mean_correlation_x_yaw = 0.0;  ///< correlation of ρ_x and φ_y
};

/// A rig's disparity offset drawn per trial, common to its points, with the spread
/// `std_px` (0: none), and whether the covariance considers it.
struct SharedOffset {
  double std_px = 0.0;
  bool considered = false;
};

/// kTrials refinements of `n` points from `source`, each started at the truth, scored
/// against it with their own covariance (and the prior, if its std > 0).
TrialStats RunTrials(const PointSource& source, int n, std::uint64_t seed,
                     double prior_std_rad = 0.0, SharedOffset offset = {}) {
  const geometry::StereoCamera c = TestCamera();
  const Eigen::Isometry3d truth = FrameMotion();
  random::Generator rng(seed);
  TrialStats s;
  double sq_x = 0.0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const double offset_px = offset.std_px > 0.0 ? offset.std_px * rng.Gaussian() : 0.0;
    const std::vector<MotionCorrespondence> corr = Measure(truth, n, source, rng, offset_px);
    Eigen::Isometry3d T = RefineMotionReprojection(corr, {}, c, truth, {}).T_curr_prev;
    MotionCovariance cov =
        EstimateMotionCovariance(corr, {}, c, T, MotionRefinementOptions{}.huber_px,
                                 offset.considered ? offset.std_px : 0.0);
    EXPECT_TRUE(cov.valid);
    if (prior_std_rad > 0.0) {
      RotationPrior prior;
      const Eigen::Vector3d noise(rng.Gaussian(), rng.Gaussian(), rng.Gaussian());
      prior.R_prev_curr = (geometry::ExpSO3(prior_std_rad * noise) * truth.linear()).transpose();
      prior.std_rad = prior_std_rad;
      AddRotationPrior(prior, &cov, &T);
    }
    const Eigen::Matrix<double, 6, 1> e = ErrorOf(truth, T);
    s.mean_nees += e.dot(cov.covariance.ldlt().solve(e)) / kTrials;
    s.mean_translation_std_m +=
        std::sqrt(cov.covariance.topLeftCorner<3, 3>().trace() / 3.0) / kTrials;
    s.mean_correlation_x_yaw +=
        cov.covariance(0, 4) / std::sqrt(cov.covariance(0, 0) * cov.covariance(4, 4)) / kTrials;
    sq_x += e(0) * e(0);
  }
  s.rms_error_x_m = std::sqrt(sq_x / kTrials);
  return s;
}

TEST(MotionCovarianceTest, WellSpreadPointsGiveASmallConsistentCovariance) {
  const TrialStats s = RunTrials(Spread(2.0, 15.0), 100, 11);
  EXPECT_GT(s.mean_nees, kMeanNeesLow);
  EXPECT_LT(s.mean_nees, kMeanNeesHigh);
  EXPECT_LT(s.mean_translation_std_m, 0.005);  // millimetres per frame
}

TEST(MotionCovarianceTest, OnlyFarPointsGiveALargeTranslationCovariance) {
  const TrialStats near = RunTrials(Spread(2.0, 15.0), 100, 12);
  const TrialStats far = RunTrials(Spread(60.0, 100.0), 100, 12);
  EXPECT_GT(far.mean_translation_std_m, 4.0 * near.mean_translation_std_m);
  // The truth agrees: the sideways error is as much larger as the covariance says.
  EXPECT_GT(far.rms_error_x_m, 4.0 * near.rms_error_x_m);
  // Disparities of 0.6–1 px, 0.42 px noise on each: depth's error is no longer linear
  // in the pixels' and the linearised covariance is optimistic (mean NEES 9.9–10.1 over
  // seeds 11–13); from 10–16 m (6–10 px) on it is inside the interval (6.03–6.09).
  EXPECT_GT(far.mean_nees, kMeanNeesLow);
  EXPECT_LT(far.mean_nees, 2.0 * 6.0);
  const TrialStats middle = RunTrials(Spread(10.0, 16.0), 100, 12);
  EXPECT_GT(middle.mean_nees, kMeanNeesLow);
  EXPECT_LT(middle.mean_nees, kMeanNeesHigh);
}

TEST(MotionCovarianceTest, FewPointsGiveALargerCovarianceThanMany) {
  const TrialStats many = RunTrials(Spread(2.0, 15.0), 100, 13);
  const TrialStats few = RunTrials(Spread(2.0, 15.0), 8, 13);
  EXPECT_GT(few.mean_translation_std_m, 2.5 * many.mean_translation_std_m);
}

TEST(MotionCovarianceTest, AFrontalWallTiesTheSidewaysTranslationToTheYaw) {
  // Every point 10 m ahead: moving sideways and turning move the image alike.
  const PointSource wall = [](random::Generator& rng) {
    const geometry::StereoCamera c = TestCamera();
    const double Z = 10.0;
    return Eigen::Vector3d((rng.Uniform(40.0, 600.0) - c.left.cx) * Z / c.left.fx,
                           (rng.Uniform(40.0, 440.0) - c.left.cy) * Z / c.left.fy, Z);
  };
  const TrialStats s = RunTrials(wall, 100, 14);
  EXPECT_GT(s.mean_nees, kMeanNeesLow);
  EXPECT_LT(s.mean_nees, kMeanNeesHigh);
  EXPECT_GT(std::abs(s.mean_correlation_x_yaw), 0.9);
  // A gyro's rotation to 0.01 deg settles the yaw, and with it the sideways motion.
  const TrialStats with_gyro = RunTrials(wall, 100, 14, 0.01 / stereo_test::kDegPerRad);
  EXPECT_GT(with_gyro.mean_nees, kMeanNeesLow);
  EXPECT_LT(with_gyro.mean_nees, kMeanNeesHigh);
  EXPECT_LT(with_gyro.rms_error_x_m, 0.5 * s.rms_error_x_m);
  EXPECT_LT(with_gyro.mean_translation_std_m, s.mean_translation_std_m);
}

TEST(MotionCovarianceTest, ASharedDisparityOffsetIsConsistentOnlyWhenConsidered) {
  // The rig's offset drawn per trial with a calibration's stated spread, 0.58 px
  // (docs/calibration.md, `typical`: principal points 0.3 px each, relative yaw
  // 1.03 mrad at fx 381 px); the test rig's fx is 500 px.
  const SharedOffset ignored{0.58, false}, considered{0.58, true};
  const TrialStats spread_off = RunTrials(Spread(2.0, 15.0), 100, 16, 0.0, ignored);
  const TrialStats spread_on = RunTrials(Spread(2.0, 15.0), 100, 16, 0.0, considered);
  EXPECT_GT(spread_off.mean_nees, kMeanNeesHigh);  // the pixels' noise alone: optimistic
  EXPECT_GT(spread_on.mean_nees, kMeanNeesLow);
  EXPECT_LT(spread_on.mean_nees, kMeanNeesHigh);
  // The offset scales the depths: the forward translation's spread grows, the more so
  // the farther the points.
  EXPECT_GT(spread_on.mean_translation_std_m, spread_off.mean_translation_std_m);
  // Points 10–16 m away (disparities of 3.8–6 px): an offset of 0.58 px is a tenth of
  // the disparity and the depth's error is no longer linear in it, so the considered
  // covariance is somewhat optimistic (mean NEES 7.04 on seed 16), far less than the
  // pixels' alone (29.0; on the 2–15 m points 21.5 ignored, 5.90 considered).
  const TrialStats middle_off = RunTrials(Spread(10.0, 16.0), 100, 16, 0.0, ignored);
  const TrialStats middle_on = RunTrials(Spread(10.0, 16.0), 100, 16, 0.0, considered);
  EXPECT_GT(middle_on.mean_nees, kMeanNeesLow);
  EXPECT_LT(middle_on.mean_nees, 1.25 * kMeanNeesHigh);
  EXPECT_GT(middle_off.mean_nees, 2.0 * middle_on.mean_nees);
}

TEST(MotionCovarianceTest, TooFewPointsOrAWrongMaskGiveNoCovariance) {
  const geometry::StereoCamera c = TestCamera();
  random::Generator rng(15);
  const std::vector<MotionCorrespondence> two = Measure(FrameMotion(), 2, Spread(2, 15), rng);
  EXPECT_FALSE(EstimateMotionCovariance(two, {}, c, FrameMotion(), 1.0).valid);
  EXPECT_THROW(EstimateMotionCovariance(two, {1}, c, FrameMotion(), 1.0), std::invalid_argument);
  // A mask that keeps two of ten points.
  const std::vector<MotionCorrespondence> ten = Measure(FrameMotion(), 10, Spread(2, 15), rng);
  std::vector<unsigned char> mask(10, 0);
  mask[0] = mask[1] = 1;
  EXPECT_FALSE(EstimateMotionCovariance(ten, mask, c, FrameMotion(), 1.0).valid);
  MotionCovariance none;
  Eigen::Isometry3d T = FrameMotion();
  EXPECT_THROW(AddRotationPrior({}, &none, &T), std::invalid_argument);
}

TEST(MotionCovarianceTest, ChangeOfFrameMatchesTheExactIncrement) {
  const Eigen::Isometry3d T_ba =
      Pose(Eigen::Vector3d(0.3, -1.2, 0.5), Eigen::Vector3d(0.2, -0.1, 0.7));
  Eigen::Matrix<double, 6, 1> delta;
  delta << 1e-6, -2e-6, 0.5e-6, 2e-6, 1e-6, -1.5e-6;
  const Eigen::Isometry3d E = ApplyIncrement(delta, Eigen::Isometry3d::Identity());
  const Eigen::Matrix<double, 6, 1> in_b =
      ErrorOf(T_ba * E * T_ba.inverse(), Eigen::Isometry3d::Identity());
  const MotionCovarianceMatrix got = TransformMotionCovariance(delta * delta.transpose(), T_ba);
  const MotionCovarianceMatrix want = in_b * in_b.transpose();
  EXPECT_LT((got - want).norm(), 1e-4 * want.norm());  // second order in δ
}

}  // namespace
}  // namespace trackbed::estimation
