// The stereo motion-estimation unit (stereo_motion_estimation.h) on synthetic
// correspondences with a known motion: the camera model and the reprojection Jacobian
// (against numeric differences), RANSAC with Horn on correspondences with 50 % outliers,
// the reprojection refinement from a perturbed start and on noisy stereo, and
// EstimateStereoMotion: a known motion recovered from noisy stereo with gross outliers
// that are rejected, its documented failures (too few correspondences, a degenerate
// configuration, no consensus), a second consensus among the candidates outside the
// first, determinism, and its argument checks.
#include "trackbed/estimation/stereo_motion_estimation.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "stereo_test_rig.h"
#include "trackbed/common/option_error.h"
#include "trackbed/common/random.h"
#include "trackbed/estimation/absolute_orientation.h"
#include "trackbed/estimation/stereo_visual_odometry.h"

namespace trackbed::estimation {
namespace {

using stereo_test::kDegPerRad;
using stereo_test::Pose;
using stereo_test::RotationErrorDeg;
using stereo_test::TestCamera;
using stereo_test::TranslationError;

/// Points in front of the camera, visible in both images, 2–40 m away.
std::vector<Eigen::Vector3d> RandomPoints(int n, random::Generator& rng) {
  const geometry::StereoCamera c = TestCamera();
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const double Z = rng.Uniform(2.0, 40.0);
    points.emplace_back((rng.Uniform(40.0, 600.0) - c.left.cx) * Z / c.left.fx,
                        (rng.Uniform(20.0, 460.0) - c.left.cy) * Z / c.left.fy, Z);
  }
  return points;
}

// ---------------------------------------------------------------------------------------
// Camera model and Jacobian.

TEST(StereoCameraTest, TriangulateInvertsProject) {
  const geometry::StereoCamera c = TestCamera();
  random::Generator rng(1);
  for (const Eigen::Vector3d& p : RandomPoints(50, rng)) {
    const Eigen::Vector3d z = c.Project(p);
    EXPECT_NEAR(z.x() - z.z(), c.left.fx * c.baseline_m / p.z(), 1e-9);  // disparity = fx·b/Z
    const Eigen::Vector3d back = c.Triangulate(z.x(), z.y(), z.x() - z.z());
    EXPECT_LT((back - p).norm(), 1e-9 * p.norm());
  }
}

TEST(StereoCameraTest, VisualOdometryRefusesACameraWithoutFocalLengthOrBaseline) {
  EXPECT_THROW(StereoVisualOdometry(geometry::StereoCamera{}), std::invalid_argument);
  geometry::StereoCamera c = TestCamera();
  c.baseline_m = -0.1;
  EXPECT_THROW(StereoVisualOdometry{c}, std::invalid_argument);
}

TEST(StereoReprojectionTest, AnalyticJacobianMatchesCentralDifferences) {
  const geometry::StereoCamera c = TestCamera();
  random::Generator rng(2);
  const auto n = [](random::Generator& g) { return g.Gaussian(); };
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Isometry3d T = Pose(0.05 * Eigen::Vector3d(n(rng), n(rng), n(rng)),
                                     Eigen::Vector3d(n(rng), n(rng), n(rng)) * 0.3);
    MotionCorrespondence m;
    m.p_prev = RandomPoints(1, rng)[0];
    m.z_curr = c.Project(T * m.p_prev) + Eigen::Vector3d(n(rng), n(rng), n(rng));
    Eigen::Matrix<double, 3, 6> J;
    StereoReprojectionResidual(c, T, m, &J);
    Eigen::Matrix<double, 3, 6> numeric;
    const double h = 1e-6;
    for (int k = 0; k < 6; ++k) {
      MotionIncrement d = MotionIncrement::Zero();
      d(k) = h;
      const Eigen::Vector3d plus = StereoReprojectionResidual(c, ApplyIncrement(d, T), m);
      d(k) = -h;
      const Eigen::Vector3d minus = StereoReprojectionResidual(c, ApplyIncrement(d, T), m);
      numeric.col(k) = (plus - minus) / (2.0 * h);
    }
    EXPECT_LT((J - numeric).norm(), 1e-5 * (1.0 + J.norm())) << "trial " << trial << "\n"
                                                             << J << "\n"
                                                             << numeric;
  }
}

TEST(StereoReprojectionTest, IncrementRoundTrips) {
  const Eigen::Isometry3d T = Pose({0.1, -0.2, 0.3}, {1.0, 2.0, 3.0});
  const Eigen::Isometry3d same = ApplyIncrement(MotionIncrement::Zero(), T);
  EXPECT_TRUE(same.matrix().isApprox(T.matrix(), 1e-15));
  MotionIncrement d;
  d << 0.01, -0.02, 0.03, 0.004, -0.005, 0.006;
  const Eigen::Isometry3d forth = ApplyIncrement(d, T);
  // Undoing: Exp(−φ) applied to (R', t' − ρ).
  Eigen::Isometry3d shifted = forth;
  shifted.translation() -= d.head<3>();
  MotionIncrement rotate_back = MotionIncrement::Zero();
  rotate_back.tail<3>() = -d.tail<3>();
  EXPECT_TRUE(ApplyIncrement(rotate_back, shifted).matrix().isApprox(T.matrix(), 1e-12));
  EXPECT_NEAR(RotationErrorDeg(forth, T), d.tail<3>().norm() * kDegPerRad, 1e-9);
}

// ---------------------------------------------------------------------------------------
// RANSAC and refinement on exact correspondences.

struct Synthetic {
  std::vector<MotionCorrespondence> correspondences;
  std::vector<bool> inlier;
};

/// `n` correspondences under T_curr_prev; a fraction `outliers` of them paired with an
/// unrelated point (both its 3-D point and its observation).
Synthetic MakeCorrespondences(const Eigen::Isometry3d& T_curr_prev, int n, double outliers,
                              random::Generator& rng) {
  const geometry::StereoCamera c = TestCamera();
  Synthetic s;
  const std::vector<Eigen::Vector3d> prev = RandomPoints(n, rng);
  const auto coin = [](random::Generator& g) { return g.Uniform(); };
  for (int i = 0; i < n; ++i) {
    MotionCorrespondence m;
    m.p_prev = prev[static_cast<std::size_t>(i)];
    const bool inlier = coin(rng) >= outliers;
    m.p_curr = inlier ? T_curr_prev * m.p_prev : RandomPoints(1, rng)[0];
    m.z_curr = c.Project(m.p_curr);
    s.correspondences.push_back(m);
    s.inlier.push_back(inlier);
  }
  return s;
}

TEST(MotionRansacTest, RecoversSixDofMotionWithHalfOutliers) {
  random::Generator data_rng(3);
  const Eigen::Isometry3d truth = Pose({0.02, -0.08, 0.01}, {0.15, -0.04, 0.9});
  const Synthetic s = MakeCorrespondences(truth, 200, 0.5, data_rng);
  int true_inliers = 0;
  for (bool b : s.inlier) true_inliers += b ? 1 : 0;
  ASSERT_GT(true_inliers, 80);
  ASSERT_LT(true_inliers, 120);

  random::Generator rng(42);
  MotionRansacResult result;
  EstimateMotionRansac(s.correspondences, TestCamera(), MotionRansacOptions{}, rng, &result);
  ASSERT_TRUE(result.success);
  EXPECT_LT(RotationErrorDeg(result.T_curr_prev, truth), 0.1);
  EXPECT_LT(TranslationError(result.T_curr_prev, truth), 1e-3);
  EXPECT_EQ(result.inliers, true_inliers);
  for (std::size_t i = 0; i < s.inlier.size(); ++i) {
    EXPECT_EQ(result.inlier_mask[i] != 0, s.inlier[i]) << "correspondence " << i;
  }
  EXPECT_LT(result.iterations, MotionRansacOptions{}.max_iterations);  // stopped early

  // The same seed gives the same answer.
  random::Generator again(42);
  MotionRansacResult second;
  EstimateMotionRansac(s.correspondences, TestCamera(), MotionRansacOptions{}, again, &second);
  EXPECT_EQ(second.iterations, result.iterations);
  EXPECT_TRUE(second.T_curr_prev.matrix() == result.T_curr_prev.matrix());
}

TEST(MotionRansacTest, TooFewOrDegenerateCorrespondencesFail) {
  random::Generator rng(5);
  MotionRansacResult result;
  std::vector<MotionCorrespondence> two(2);
  EstimateMotionRansac(two, TestCamera(), MotionRansacOptions{}, rng, &result);
  EXPECT_FALSE(result.success);
  EXPECT_EQ(result.inliers, 0);
  // All points on one line: every sample is degenerate for Horn.
  std::vector<MotionCorrespondence> collinear;
  for (int i = 0; i < 10; ++i) {
    MotionCorrespondence m;
    m.p_prev = Eigen::Vector3d(0.1 * i, 0.0, 5.0 + i);
    m.p_curr = m.p_prev;
    m.z_curr = TestCamera().Project(m.p_curr);
    collinear.push_back(m);
  }
  EstimateMotionRansac(collinear, TestCamera(), MotionRansacOptions{}, rng, &result);
  EXPECT_FALSE(result.success);
  EXPECT_TRUE(result.T_curr_prev.matrix().isIdentity());
}

TEST(MotionRefinementTest, ConvergesToTheTrueMotionFromAPerturbedStart) {
  random::Generator rng(6);
  const Eigen::Isometry3d truth = Pose({-0.03, 0.05, 0.02}, {0.2, 0.05, 1.1});
  const Synthetic s = MakeCorrespondences(truth, 80, 0.0, rng);
  // 2° and 15 cm off.
  const Eigen::Isometry3d start = Pose({0.0, 2.0 / kDegPerRad, 0.0}, {0.1, -0.05, 0.0}) * truth;
  ASSERT_GT(RotationErrorDeg(start, truth), 1.9);
  const MotionRefinementResult r = RefineMotionReprojection(s.correspondences, {}, TestCamera(),
                                                            start, MotionRefinementOptions{});
  EXPECT_TRUE(r.converged);
  EXPECT_LT(RotationErrorDeg(r.T_curr_prev, truth), 1e-6);
  EXPECT_LT(TranslationError(r.T_curr_prev, truth), 1e-7);
  EXPECT_GT(r.initial_rms_px, 1.0);
  EXPECT_LT(r.final_rms_px, 1e-6);
  EXPECT_LE(r.iterations, MotionRefinementOptions{}.max_iterations);
}

TEST(MotionRefinementTest, ReducesTheErrorOfHornOnNoisyStereo) {
  // With pixel noise, Horn on triangulated points suffers from the far points' depth
  // noise (σ_Z ∝ Z², even with inverse-variance weights as in RANSAC's refit); the
  // reprojection error is what the measurements constrain.
  const geometry::StereoCamera c = TestCamera();
  random::Generator rng(7);
  const auto noise = [](random::Generator& g) { return 0.3 * g.Gaussian(); };
  const Eigen::Isometry3d truth = Pose({0.01, 0.03, 0.0}, {0.05, 0.0, 0.5});
  double horn_error = 0.0, refined_error = 0.0;
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<MotionCorrespondence> cs;
    std::vector<Eigen::Vector3d> src, dst;
    std::vector<double> weights;
    for (const Eigen::Vector3d& p : RandomPoints(150, rng)) {
      const Eigen::Vector3d z0 = c.Project(p) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      const Eigen::Vector3d z1 =
          c.Project(truth * p) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      if (z0.x() - z0.z() < 1.0 || z1.x() - z1.z() < 1.0) continue;
      MotionCorrespondence m;
      m.p_prev = c.Triangulate(z0.x(), z0.y(), z0.x() - z0.z());
      m.p_curr = c.Triangulate(z1.x(), z1.y(), z1.x() - z1.z());
      m.z_curr = z1;
      cs.push_back(m);
      src.push_back(m.p_prev);
      dst.push_back(m.p_curr);
      weights.push_back(1.0 / (std::pow(m.p_prev.z(), 4) + std::pow(m.p_curr.z(), 4)));
    }
    const Eigen::Isometry3d horn = HornAbsoluteOrientation(src, dst, false, weights)->Rigid();
    const MotionRefinementResult r =
        RefineMotionReprojection(cs, {}, c, horn, MotionRefinementOptions{});
    horn_error += TranslationError(horn, truth);
    refined_error += TranslationError(r.T_curr_prev, truth);
  }
  EXPECT_LT(refined_error, 0.5 * horn_error);
  std::printf("mean translation error: Horn %.1f mm, refined %.1f mm\n", 100.0 * horn_error,
              100.0 * refined_error);
}

TEST(MotionRefinementTest, MaskOfTheWrongSizeThrows) {
  std::vector<MotionCorrespondence> cs(4);
  EXPECT_THROW(RefineMotionReprojection(cs, std::vector<unsigned char>(3, 1), TestCamera(),
                                        Eigen::Isometry3d::Identity(), MotionRefinementOptions{}),
               std::invalid_argument);
}

// ---------------------------------------------------------------------------------------
// EstimateStereoMotion: RANSAC and refinement together.

/// Correspondences as a stereo front end measures them: `n` points 2–15 m away (every
/// disparity >= 4 px) seen before and after the motion `truth`, each pixel coordinate
/// with Gaussian noise of sigma_px, both 3-D points triangulated from the noisy pixels.
/// A fraction `outliers` are gross mismatches: the current measurement is of an
/// unrelated point (as when LK jumps to another corner), far off any motion's prediction.
struct NoisyStereo {
  std::vector<MotionCorrespondence> correspondences;
  std::vector<bool> outlier;
  int outliers = 0;
};

NoisyStereo MakeNoisyStereo(const Eigen::Isometry3d& truth, int n, double outliers, double sigma_px,
                            random::Generator& rng) {
  const geometry::StereoCamera c = TestCamera();
  const auto coin = [](random::Generator& g) { return g.Uniform(); };
  const auto noise = [](random::Generator& g) {
    return g.Gaussian();
  };  // scaled: sigma_px may be 0
  const auto random_point = [&]() {
    const double Z = rng.Uniform(2.0, 15.0);
    return Eigen::Vector3d((rng.Uniform(60.0, 580.0) - c.left.cx) * Z / c.left.fx,
                           (rng.Uniform(40.0, 440.0) - c.left.cy) * Z / c.left.fy, Z);
  };
  const auto measure = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d e(noise(rng), noise(rng), noise(rng));
    return Eigen::Vector3d(c.Project(p) + sigma_px * e);
  };
  NoisyStereo s;
  while (static_cast<int>(s.correspondences.size()) < n) {
    const Eigen::Vector3d p = random_point();
    const bool outlier = coin(rng) < outliers;
    const Eigen::Vector3d q = outlier ? random_point() : Eigen::Vector3d(truth * p);
    const Eigen::Vector3d z0 = measure(p), z1 = measure(q);
    if (!(q.z() > 1.0) || z1.x() < 0.0 || z1.x() > 639.0 || z1.y() < 0.0 || z1.y() > 479.0) {
      continue;  // left the current view
    }
    MotionCorrespondence m;
    m.p_prev = c.Triangulate(z0.x(), z0.y(), z0.x() - z0.z());
    m.p_curr = c.Triangulate(z1.x(), z1.y(), z1.x() - z1.z());
    m.z_curr = z1;
    s.correspondences.push_back(m);
    s.outlier.push_back(outlier);
    s.outliers += outlier ? 1 : 0;
  }
  return s;
}

TEST(StereoMotionEstimationTest, RecoversAKnownMotionFromNoisyStereoAndRejectsGrossOutliers) {
  // 0.2 px noise on every pixel coordinate (sub-pixel LK and stereo matching) and 30 %
  // gross outliers; a motion of 1 m with 4.6° of rotation about a tilted axis. Ten data
  // seeds. Tolerances 0.1° and 3 cm (3 % of the motion): data seeds 11–40 with RANSAC
  // seeds 1–3 (90 draws) give at most 0.071° and 23 mm. The
  // rig's short baseline makes 3-point hypotheses from triangulated points poor as the
  // noise grows: at 0.5 px RANSAC's best consensus has about 10 inliers and the motion
  // ends tenths of a metre off.
  const Eigen::Isometry3d truth = Pose({0.02, -0.075, 0.012}, {0.12, -0.05, 0.98});
  for (std::uint64_t seed = 11; seed <= 20; ++seed) {
    SCOPED_TRACE("data seed " + std::to_string(seed));
    random::Generator data_rng(seed);
    const NoisyStereo s = MakeNoisyStereo(truth, 200, 0.3, 0.2, data_rng);
    ASSERT_GT(s.outliers, 45);  // the fraction drawn is about 30 %
    ASSERT_LT(s.outliers, 75);

    random::Generator rng(1);
    StereoMotionResult result;
    EstimateStereoMotion(s.correspondences, {}, TestCamera(), StereoMotionOptions{}, rng, &result);
    ASSERT_TRUE(result.ok()) << ToString(result.status);
    EXPECT_LT(RotationErrorDeg(result.T_curr_prev, truth), 0.1);
    EXPECT_LT(TranslationError(result.T_curr_prev, truth), 0.03);
    EXPECT_TRUE(result.T_curr_prev.linear().isUnitary(1e-12));

    // Every gross outlier is rejected; nearly every true correspondence is kept (the 90
    // draws above: at least 86 %).
    const int true_inliers = static_cast<int>(s.correspondences.size()) - s.outliers;
    int kept = 0;
    ASSERT_EQ(result.inlier_mask.size(), s.correspondences.size());
    for (std::size_t i = 0; i < s.outlier.size(); ++i) {
      if (s.outlier[i]) {
        EXPECT_EQ(result.inlier_mask[i], 0) << "gross outlier " << i << " kept";
      } else {
        kept += result.inlier_mask[i] ? 1 : 0;
      }
    }
    EXPECT_EQ(result.inliers, kept);
    EXPECT_GE(kept, static_cast<int>(0.8 * true_inliers));
    EXPECT_EQ(result.candidates, static_cast<int>(s.correspondences.size()));
    // The refinement leaves residuals of the order of the noise: σ = 0.2 px per
    // coordinate in z_curr plus p_prev's triangulation error carried through the
    // motion, which no motion absorbs (0.58 px for seed 11).
    EXPECT_LT(result.refinement.final_rms_px, 1.0);
    EXPECT_LE(result.refinement.final_rms_px, result.refinement.initial_rms_px);
  }
}

TEST(StereoMotionEstimationTest, CandidatesOutsideTheFirstConsensusGiveTheSecondMotion) {
  // 120 background points move by the camera's motion, 60 on an object by another one:
  // the first consensus is the background's; restricted to the rest, the object's.
  random::Generator data_rng(14);
  const Eigen::Isometry3d camera_motion = Pose({0.0, 0.03, 0.0}, {0.05, 0.0, 0.6});
  const Eigen::Isometry3d object_motion = Pose({0.0, -0.02, 0.0}, {-0.4, 0.0, 0.9});
  const NoisyStereo background = MakeNoisyStereo(camera_motion, 120, 0.0, 0.2, data_rng);
  const NoisyStereo object = MakeNoisyStereo(object_motion, 60, 0.0, 0.2, data_rng);
  std::vector<MotionCorrespondence> all = background.correspondences;
  all.insert(all.end(), object.correspondences.begin(), object.correspondences.end());

  random::Generator rng(6);
  StereoMotionResult first;
  EstimateStereoMotion(all, {}, TestCamera(), StereoMotionOptions{}, rng, &first);
  ASSERT_TRUE(first.ok());
  EXPECT_LT(TranslationError(first.T_curr_prev, camera_motion), 0.01);

  std::vector<unsigned char> candidates(all.size());
  int outside = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    candidates[i] = first.inlier_mask[i] ? 0 : 1;
    outside += candidates[i];
  }
  StereoMotionResult second;
  EstimateStereoMotion(all, candidates, TestCamera(), StereoMotionOptions{}, rng, &second);
  ASSERT_TRUE(second.ok()) << ToString(second.status);
  EXPECT_EQ(second.candidates, outside);
  EXPECT_LT(TranslationError(second.T_curr_prev, object_motion), 0.02);
  EXPECT_LT(RotationErrorDeg(second.T_curr_prev, object_motion), 0.1);
  ASSERT_EQ(second.ransac.inlier_mask.size(), all.size());
  int non_candidates_in_consensus = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    non_candidates_in_consensus += !candidates[i] && second.ransac.inlier_mask[i] ? 1 : 0;
  }
  EXPECT_EQ(non_candidates_in_consensus, 0);
  // The object's points, not the background's, are the second motion's inliers.
  int object_inliers = 0, background_inliers = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    (i < 120 ? background_inliers : object_inliers) += second.inlier_mask[i] ? 1 : 0;
  }
  EXPECT_GE(object_inliers, 48);  // at least 80 % of the object's 60
  EXPECT_EQ(background_inliers, 0);
}

TEST(StereoMotionEstimationTest, BadArgumentsThrow) {
  std::vector<MotionCorrespondence> cs(8);
  random::Generator rng(7);
  StereoMotionResult result;
  EXPECT_THROW(EstimateStereoMotion(cs, std::vector<unsigned char>(7, 1), TestCamera(),
                                    StereoMotionOptions{}, rng, &result),
               std::invalid_argument);
  const auto field = [&](const StereoMotionOptions& options) -> std::string {
    try {
      EstimateStereoMotion(cs, {}, TestCamera(), options, rng, &result);
    } catch (const OptionError& e) {
      return e.field();
    }
    return "";
  };
  StereoMotionOptions o;
  o.min_inliers = 2;
  EXPECT_EQ(field(o), "min_inliers");
  o = {};
  o.ransac.threshold_px = 0.0;
  EXPECT_EQ(field(o), "ransac.threshold_px");
  o = {};
  o.refinement.huber_px = -1.0;
  EXPECT_EQ(field(o), "refinement.huber_px");
}

// A point's observations (u_left, v, u_right) before and after a motion.
struct Observed {
  Eigen::Vector3d z0, z1;
};

// Points 3–60 m away seen before and after `truth` by a rig whose measured disparities
// read `offset_px` less than the true ones (a rectification's error), with Gaussian
// noise of 0.2 px on every coordinate.
std::vector<Observed> OffsetStereo(const Eigen::Isometry3d& truth, double offset_px,
                                   random::Generator& rng) {
  const geometry::StereoCamera c = stereo_test::TestCamera();
  std::vector<Observed> out;
  const auto noise = [&rng] {
    return Eigen::Vector3d(0.2 * rng.Gaussian(), 0.2 * rng.Gaussian(), 0.2 * rng.Gaussian());
  };
  while (out.size() < 150) {
    const double Z = rng.Uniform(3.0, 60.0);
    const Eigen::Vector3d p((rng.Uniform(60.0, 580.0) - c.left.cx) * Z / c.left.fx,
                            (rng.Uniform(40.0, 440.0) - c.left.cy) * Z / c.left.fy, Z);
    const Eigen::Vector3d q = truth * p;
    const Eigen::Vector3d z1 = c.Project(q);
    if (!(q.z() > 1.0) || z1.x() < 0.0 || z1.x() > 639.0 || z1.y() < 0.0 || z1.y() > 479.0) {
      continue;
    }
    const Eigen::Vector3d offset(0.0, 0.0, offset_px);  // u_right: the disparity reads less
    out.push_back({c.Project(p) + offset + noise(), z1 + offset + noise()});
  }
  return out;
}

// The correspondences a front end builds from them with its current estimate of the
// offset, as StereoVisualOdometry does.
std::vector<MotionCorrespondence> Corrected(const std::vector<Observed>& observed,
                                            double estimate_px) {
  const geometry::StereoCamera c = stereo_test::TestCamera();
  const Eigen::Vector3d shift(0.0, 0.0, estimate_px);
  std::vector<MotionCorrespondence> out;
  for (const Observed& o : observed) {
    MotionCorrespondence m;
    m.z_prev = o.z0 - shift;
    m.z_curr = o.z1 - shift;
    m.p_prev = c.Triangulate(m.z_prev.x(), m.z_prev.y(), m.z_prev.x() - m.z_prev.z());
    m.p_curr = c.Triangulate(m.z_curr.x(), m.z_curr.y(), m.z_curr.x() - m.z_curr.z());
    out.push_back(m);
  }
  return out;
}

TEST(DisparityOffsetTest, AnOffsetThatScalesTheMotionIsFoundFromPointsAtManyDepths) {
  const geometry::StereoCamera c = stereo_test::TestCamera();
  const Eigen::Isometry3d truth =
      Pose(Eigen::Vector3d(0.01, -0.02, 0.005), Eigen::Vector3d(0.03, -0.01, 1.2));
  for (const double offset : {0.0, 0.3, -0.5}) {
    random::Generator rng(7);
    const std::vector<Observed> observed = OffsetStereo(truth, offset, rng);
    // Without the offset the motion's scale is wrong by a percent or more.
    const MotionRefinementResult raw =
        RefineMotionReprojection(Corrected(observed, 0.0), {}, c, truth, {});
    const double raw_error = std::abs(raw.T_curr_prev.translation().norm() - 1.2);
    if (offset != 0.0) {
      EXPECT_GT(raw_error, 0.012) << offset;
    }
    // Measure, correct, refine again: the steps StereoVisualOdometry takes frame by frame.
    double estimate = 0.0, variance = 0.0;
    Eigen::Isometry3d T = raw.T_curr_prev;
    for (int step = 0; step < 4; ++step) {
      const std::vector<MotionCorrespondence> s = Corrected(observed, estimate);
      T = RefineMotionReprojection(s, {}, c, T, {}).T_curr_prev;
      const DisparityOffsetMeasurement m = MeasureDisparityOffset(s, {}, c, T, 1.0);
      ASSERT_TRUE(m.valid);
      estimate += m.offset_px;
      variance = m.variance_px2;
    }
    // One frame's 150 points with 0.2 px of noise: over seeds 1-40 (offset 0) its
    // measurements have an RMS of 0.037 px about the truth (a mean of +0.028 px: the
    // noise of the far points' depths) where its variance says 0.024 px; frames average
    // the noise away.
    EXPECT_NEAR(estimate, offset, 0.1) << offset;
    EXPECT_LT(std::sqrt(variance), 0.05);
    T = RefineMotionReprojection(Corrected(observed, estimate), {}, c, T, {}).T_curr_prev;
    if (offset != 0.0) {
      EXPECT_LT(std::abs(T.translation().norm() - 1.2), 0.5 * raw_error) << offset;
    }
  }
}

TEST(DisparityOffsetTest, WithoutTranslationOrPointsThereIsNoMeasurement) {
  const geometry::StereoCamera c = stereo_test::TestCamera();
  random::Generator rng(3);
  const Eigen::Isometry3d ahead = Pose(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 1.2));
  const Eigen::Isometry3d turn = Pose(Eigen::Vector3d(0.0, 0.02, 0.0), Eigen::Vector3d::Zero());
  // A rotation about the camera moves every point's image alike whatever its depth:
  // nothing tells δ from zero.
  const DisparityOffsetMeasurement moving =
      MeasureDisparityOffset(Corrected(OffsetStereo(ahead, 0.4, rng), 0.0), {}, c, ahead, 1.0);
  const std::vector<MotionCorrespondence> turning = Corrected(OffsetStereo(turn, 0.4, rng), 0.0);
  const DisparityOffsetMeasurement turned = MeasureDisparityOffset(turning, {}, c, turn, 1.0);
  ASSERT_TRUE(moving.valid);
  EXPECT_LT(turned.information, 0.01 * moving.information);
  const std::vector<MotionCorrespondence> few(turning.begin(),
                                              turning.begin() + kMinDisparityOffsetPoints - 1);
  EXPECT_FALSE(MeasureDisparityOffset(few, {}, c, turn, 1.0).valid);
}

}  // namespace
}  // namespace trackbed::estimation
