// The running scores equal the batch functions of trajectory_metrics.h on the whole
// trajectories: bit for bit where the sums run in the same order, and the SE(3)-aligned
// ATE (from moments) to rounding; and the drift window holds only the last 10 m.
#include "trackbed/estimation/running_trajectory_score.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "trackbed/common/option_error.h"
#include "trackbed/estimation/trajectory_metrics.h"

namespace trackbed::estimation {
namespace {

// A winding drive far from the origin (as a kilometre route's end) at 0.4 m/s and
// 100 Hz, and an estimate that drifts in heading and scale with noise, climbing 0.5 m.
void WindingRun(int n, Trajectory* gt, Trajectory* est) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  double yaw = 0.3, est_yaw = 0.3;
  Eigen::Vector3d p(812.0, -455.0, 31.0), q = p;
  for (int k = 0; k < n; ++k) {
    const double t = 0.01 * k;
    const double rate = 0.4 * std::sin(0.05 * t);
    yaw += rate * 0.01;
    est_yaw += rate * 1.02 * 0.01 + 1e-5;
    p += 0.004 * Eigen::Vector3d(std::cos(yaw), std::sin(yaw), 0.0005);
    q += 0.00403 * Eigen::Vector3d(std::cos(est_yaw), std::sin(est_yaw), 0.0);
    Eigen::Isometry3d T_gt = Eigen::Isometry3d::Identity(), T_est = T_gt;
    T_gt.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T_gt.translation() = p;
    T_est.linear() = Eigen::AngleAxisd(est_yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T_est.translation() = q + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    gt->push_back({t, T_gt});
    est->push_back({t, T_est});
  }
}

TEST(RunningTrajectoryScoreTest, EqualsTheBatchFiguresOfTheWholeTrajectories) {
  Trajectory gt, est;
  WindingRun(20000, &gt, &est);  // 200 s, 80 m
  RunningTrajectoryScore score;
  for (std::size_t k = 0; k < gt.size(); ++k) score.Add(gt[k].T_world_body, est[k].T_world_body);
  EXPECT_EQ(score.count(), 20000);
  // The same sums in the same order: identical.
  EXPECT_EQ(score.horizontal_ate_rmse_m(), HorizontalAteRmse(gt, est));
  EXPECT_EQ(score.final_horizontal_error_m(), ComputeFinalError(gt, est).horizontal_m);
  EXPECT_EQ(score.true_path_length_m(), PathLength(gt));
  ASSERT_TRUE(score.rpe_trans_pct().has_value());
  EXPECT_EQ(*score.rpe_trans_pct(), *RpeTransPct(gt, est));
  // From moments: rounding only (about 1e-12 relative here, far from the origin).
  const double batch = AbsoluteTrajectoryError(gt, est, AlignmentMode::kSe3).error_m.rmse;
  EXPECT_GT(batch, 0.05);
  EXPECT_NEAR(score.se3_ate_rmse_m(), batch, 1e-9 * batch);
}

TEST(RunningTrajectoryScoreTest, DriftWindowHoldsTheLastSegmentOfPathOnly) {
  Trajectory gt, est;
  WindingRun(60000, &gt, &est);  // 240 m
  RunningTrajectoryScore score;
  std::size_t largest = 0;
  for (std::size_t k = 0; k < gt.size(); ++k) {
    score.Add(gt[k].T_world_body, est[k].T_world_body);
    largest = std::max(largest, score.window_size());
  }
  // 10 m at 4 mm per pose: 2500 poses (a few more for the path's rounding).
  EXPECT_LE(largest, 2503u);
  EXPECT_GE(largest, 2500u);
}

TEST(RunningTrajectoryScoreTest, ShortPathHasNoDriftAndEmptyScoresZero) {
  RunningTrajectoryScore score;
  EXPECT_EQ(score.horizontal_ate_rmse_m(), 0.0);
  EXPECT_EQ(score.se3_ate_rmse_m(), 0.0);
  EXPECT_FALSE(score.rpe_trans_pct().has_value());
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity(), b = a;
  b.translation() = Eigen::Vector3d(3.0, 4.0, 0.0);
  score.Add(a, a);
  score.Add(b, a);
  EXPECT_EQ(score.final_horizontal_error_m(), 5.0);
  EXPECT_FALSE(score.rpe_trans_pct().has_value());  // 5 m of path < 10 m
  EXPECT_THROW(RunningTrajectoryScore(0.0), OptionError);
}

TEST(PointPairMomentsTest, HornFromMomentsEqualsHornOnThePoints) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-20.0, 20.0);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<Eigen::Vector3d> src, dst;
  PointPairMoments m;
  for (int k = 0; k < 500; ++k) {
    src.emplace_back(u(rng) + 1000.0, u(rng), u(rng));
    dst.push_back(R * src.back() + Eigen::Vector3d(5, -6, 7) + 0.01 * Eigen::Vector3d::Random());
    m.Add(src.back(), dst.back());
  }
  const SimilarityTransform batch = HornAbsoluteOrientationAnyMinimizer(src, dst, true);
  bool unique = false;
  const SimilarityTransform moments = HornAbsoluteOrientationFromMoments(m, true, &unique);
  EXPECT_TRUE(unique);
  EXPECT_TRUE(moments.R.isApprox(batch.R, 1e-12));
  EXPECT_NEAR(moments.t.norm(), batch.t.norm(), 1e-9);
  EXPECT_NEAR(moments.scale, batch.scale, 1e-12);
  double residual = 0.0;
  for (std::size_t k = 0; k < src.size(); ++k)
    residual += (dst[k] - batch.Apply(src[k])).squaredNorm();
  // The residual from moments is a difference of sums ~1e6 times larger (spreads of
  // 20 m, errors of 1 cm): rounding of about 1e-16 × 1e6 relative.
  EXPECT_NEAR(m.ResidualSquaredSum(moments), residual, 1e-8 * residual);
  EXPECT_THROW(HornAbsoluteOrientationFromMoments(PointPairMoments{}), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::estimation
