// Horn's closed-form absolute orientation: exact recovery, agreement with Eigen::umeyama,
// optimality on noisy data, rotation invariants, weights, and degenerate inputs.
#include "trackbed/estimation/absolute_orientation.h"

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

namespace trackbed::estimation {
namespace {

using Points = std::vector<Eigen::Vector3d>;

Eigen::Matrix3d RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

Points RandomPoints(std::mt19937& rng, int count, double spread_m) {
  std::normal_distribution<double> n(0.0, spread_m);
  Points p;
  for (int i = 0; i < count; ++i) p.emplace_back(n(rng), n(rng), n(rng));
  return p;
}

Points Transform(const Points& src, const Eigen::Matrix3d& R, const Eigen::Vector3d& t, double s) {
  Points dst;
  for (const Eigen::Vector3d& p : src) dst.push_back(s * (R * p) + t);
  return dst;
}

void AddNoise(std::mt19937& rng, double sigma_m, Points* points) {
  std::normal_distribution<double> n(0.0, sigma_m);
  for (Eigen::Vector3d& p : *points) p += Eigen::Vector3d(n(rng), n(rng), n(rng));
}

// Σ |dst − T(src)|².
double Cost(const Points& src, const Points& dst, const Eigen::Matrix3d& sR,
            const Eigen::Vector3d& t) {
  double c = 0.0;
  for (std::size_t i = 0; i < src.size(); ++i) c += (dst[i] - (sR * src[i] + t)).squaredNorm();
  return c;
}

Eigen::Matrix4d Umeyama(const Points& src, const Points& dst, bool with_scale) {
  Eigen::Matrix3Xd a(3, src.size()), b(3, dst.size());
  for (std::size_t i = 0; i < src.size(); ++i) {
    a.col(static_cast<Eigen::Index>(i)) = src[i];
    b.col(static_cast<Eigen::Index>(i)) = dst[i];
  }
  return Eigen::umeyama(a, b, with_scale);
}

TEST(HornAbsoluteOrientationTest, RecoversExactRigidTransform) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    const Points src = RandomPoints(rng, 3 + trial, 5.0);
    const Eigen::Matrix3d R = RandomRotation(rng);
    const Eigen::Vector3d t = RandomPoints(rng, 1, 20.0)[0];
    const auto T = HornAbsoluteOrientation(src, Transform(src, R, t, 1.0));
    ASSERT_TRUE(T.has_value());
    EXPECT_LT((T->R - R).norm(), 1e-9);
    EXPECT_LT((T->t - t).norm(), 1e-9);
    EXPECT_EQ(T->scale, 1.0);
  }
}

TEST(HornAbsoluteOrientationTest, RecoversExactSimilarityTransform) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> scale(0.05, 20.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Points src = RandomPoints(rng, 10, 3.0);
    const Eigen::Matrix3d R = RandomRotation(rng);
    const Eigen::Vector3d t = RandomPoints(rng, 1, 20.0)[0];
    const double s = scale(rng);
    const Points dst = Transform(src, R, t, s);
    const auto T = HornAbsoluteOrientation(src, dst, /*with_scale=*/true);
    ASSERT_TRUE(T.has_value());
    EXPECT_LT((T->R - R).norm(), 1e-9);
    EXPECT_LT((T->t - t).norm(), 1e-9);
    EXPECT_NEAR(T->scale, s, 1e-9 * s);
    for (std::size_t i = 0; i < src.size(); ++i)
      EXPECT_LT((T->Apply(src[i]) - dst[i]).norm(), 1e-9);
  }
}

TEST(HornAbsoluteOrientationTest, AgreesWithUmeyamaOnExactData) {
  std::mt19937 rng(3);
  for (bool with_scale : {false, true}) {
    for (int trial = 0; trial < 30; ++trial) {
      const Points src = RandomPoints(rng, 20, 2.0);
      const Points dst =
          Transform(src, RandomRotation(rng), RandomPoints(rng, 1, 10.0)[0], with_scale ? 2.5 : 1);
      const auto T = HornAbsoluteOrientation(src, dst, with_scale);
      ASSERT_TRUE(T.has_value());
      const Eigen::Matrix4d U = Umeyama(src, dst, with_scale);
      const double s_u = U.block<3, 1>(0, 0).norm();
      EXPECT_LT((T->R - U.block<3, 3>(0, 0) / s_u).norm(), 1e-9);
      EXPECT_LT((T->t - U.block<3, 1>(0, 3)).norm(), 1e-9);
      EXPECT_NEAR(T->scale, s_u, 1e-9);
    }
  }
}

TEST(HornAbsoluteOrientationTest, CostNoWorseThanUmeyamaOnNoisyData) {
  std::mt19937 rng(4);
  for (bool with_scale : {false, true}) {
    for (int trial = 0; trial < 30; ++trial) {
      const Points src = RandomPoints(rng, 4 + trial, 2.0);
      Points dst =
          Transform(src, RandomRotation(rng), RandomPoints(rng, 1, 10.0)[0], with_scale ? 0.3 : 1);
      AddNoise(rng, 0.2, &dst);
      const auto T = HornAbsoluteOrientation(src, dst, with_scale);
      ASSERT_TRUE(T.has_value());
      const Eigen::Matrix4d U = Umeyama(src, dst, with_scale);
      const double horn = Cost(src, dst, T->scale * T->R, T->t);
      const double umeyama = Cost(src, dst, U.block<3, 3>(0, 0), U.block<3, 1>(0, 3));
      EXPECT_LE(horn, umeyama + 1e-12) << "trial " << trial << " with_scale " << with_scale;
      // Both are the unique optimum here, so they agree closely too.
      EXPECT_NEAR(horn, umeyama, 1e-9 * (1.0 + umeyama));
    }
  }
}

TEST(HornAbsoluteOrientationTest, RotationIsProperEvenForReflectedData) {
  // dst = a mirror image of src plus noise: the best orthogonal fit is a reflection, but the
  // result must be a rotation (det +1), the best one, as Umeyama's corrected SVD gives.
  std::mt19937 rng(5);
  const Eigen::Matrix3d mirror = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  for (int trial = 0; trial < 30; ++trial) {
    const Points src = RandomPoints(rng, 12, 2.0);
    Points dst = Transform(src, RandomRotation(rng) * mirror, RandomPoints(rng, 1, 5.0)[0], 1.0);
    AddNoise(rng, 0.05, &dst);
    const auto T = HornAbsoluteOrientation(src, dst);
    ASSERT_TRUE(T.has_value());
    EXPECT_NEAR(T->R.determinant(), 1.0, 1e-12);
    EXPECT_LT((T->R.transpose() * T->R - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    const Eigen::Matrix4d U = Umeyama(src, dst, false);
    EXPECT_LE(Cost(src, dst, T->R, T->t),
              Cost(src, dst, U.block<3, 3>(0, 0), U.block<3, 1>(0, 3)) + 1e-12);
  }
}

TEST(HornAbsoluteOrientationTest, InverseOfSwappedProblemOnExactData) {
  std::mt19937 rng(6);
  const Points src = RandomPoints(rng, 8, 1.0);
  const Points dst = Transform(src, RandomRotation(rng), Eigen::Vector3d(1, 2, 3), 1.7);
  const auto ab = HornAbsoluteOrientation(src, dst, true);
  const auto ba = HornAbsoluteOrientation(dst, src, true);
  ASSERT_TRUE(ab && ba);
  EXPECT_LT((ab->R * ba->R - Eigen::Matrix3d::Identity()).norm(), 1e-9);
  EXPECT_NEAR(ab->scale * ba->scale, 1.0, 1e-9);
}

TEST(HornAbsoluteOrientationTest, IntegerWeightsEqualRepeatedPoints) {
  std::mt19937 rng(7);
  const Points src = RandomPoints(rng, 6, 1.0);
  Points dst = Transform(src, RandomRotation(rng), Eigen::Vector3d(0, 1, 0), 1.3);
  AddNoise(rng, 0.1, &dst);
  const std::vector<double> weights = {1, 3, 2, 1, 0, 4};
  Points src_rep, dst_rep;
  for (std::size_t i = 0; i < src.size(); ++i) {
    for (int k = 0; k < static_cast<int>(weights[i]); ++k) {
      src_rep.push_back(src[i]);
      dst_rep.push_back(dst[i]);
    }
  }
  for (bool with_scale : {false, true}) {
    const auto weighted = HornAbsoluteOrientation(src, dst, with_scale, weights);
    const auto repeated = HornAbsoluteOrientation(src_rep, dst_rep, with_scale);
    ASSERT_TRUE(weighted && repeated);
    EXPECT_LT((weighted->R - repeated->R).norm(), 1e-9);
    EXPECT_LT((weighted->t - repeated->t).norm(), 1e-9);
    EXPECT_NEAR(weighted->scale, repeated->scale, 1e-9);
  }
}

TEST(HornAbsoluteOrientationTest, RigidDropsScale) {
  SimilarityTransform T;
  T.R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.t = Eigen::Vector3d(1, 2, 3);
  T.scale = 2.0;
  const Eigen::Isometry3d X = T.Rigid();
  EXPECT_TRUE(X.linear().isApprox(T.R));
  EXPECT_TRUE(X.translation().isApprox(T.t));
  EXPECT_TRUE(T.Apply(Eigen::Vector3d::UnitX()).isApprox(2.0 * T.R.col(0) + T.t));
}

TEST(HornAbsoluteOrientationTest, FewerThanThreePairsGiveNullopt) {
  const Points two = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_FALSE(HornAbsoluteOrientation(two, two).has_value());
  EXPECT_FALSE(HornAbsoluteOrientation({}, {}).has_value());
  // Three pairs, but one of them weightless.
  const Points three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_FALSE(HornAbsoluteOrientation(three, three, false, {1, 1, 0}).has_value());
  EXPECT_TRUE(HornAbsoluteOrientation(three, three).has_value());
}

TEST(HornAbsoluteOrientationTest, CollinearOrCoincidentPointsGiveNullopt) {
  const Points line = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {-3, -3, -3}};
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  const Points moved = Transform(line, R, Eigen::Vector3d(4, 5, 6), 1.0);
  EXPECT_FALSE(HornAbsoluteOrientation(line, moved).has_value());
  EXPECT_FALSE(HornAbsoluteOrientation(line, moved, true).has_value());
  const Points same(5, Eigen::Vector3d(1, 2, 3));
  EXPECT_FALSE(HornAbsoluteOrientation(same, same).has_value());
  // Non-collinear src but collinear dst: the rotation about dst's line is free.
  const Points plane = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  EXPECT_FALSE(HornAbsoluteOrientation(plane, line).has_value());
  // Planar but not collinear is fine.
  EXPECT_TRUE(HornAbsoluteOrientation(plane, Transform(plane, R, Eigen::Vector3d::Zero(), 1.0))
                  .has_value());
}

TEST(HornAbsoluteOrientationTest, AnyMinimizerStillFitsCollinearPoints) {
  const Points line = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {-3, -3, -3}};
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  const Points moved = Transform(line, R, Eigen::Vector3d(4, 5, 6), 2.0);
  bool unique = true;
  const SimilarityTransform T = HornAbsoluteOrientationAnyMinimizer(line, moved, true, {}, &unique);
  EXPECT_FALSE(unique);
  EXPECT_NEAR(T.R.determinant(), 1.0, 1e-12);
  EXPECT_NEAR(T.scale, 2.0, 1e-9);
  for (std::size_t i = 0; i < line.size(); ++i)
    EXPECT_LT((T.Apply(line[i]) - moved[i]).norm(), 1e-9);
  EXPECT_THROW(HornAbsoluteOrientationAnyMinimizer({}, {}), std::invalid_argument);
}

TEST(HornAbsoluteOrientationTest, BadArgumentsThrowNamingTheFunction) {
  const Points three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const Points two = {{0, 0, 0}, {1, 0, 0}};
  try {
    HornAbsoluteOrientation(three, two);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "HornAbsoluteOrientation: src has 3 points but dst has 2");
  }
  EXPECT_THROW(HornAbsoluteOrientation(three, three, false, {1, 1}), std::invalid_argument);
  EXPECT_THROW(HornAbsoluteOrientation(three, three, false, {1, -1, 1}), std::invalid_argument);
  Points bad = three;
  bad[1].x() = std::nan("");
  EXPECT_THROW(HornAbsoluteOrientation(bad, three), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::estimation
