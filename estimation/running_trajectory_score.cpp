// Trajectory figures accumulated pose by pose (see running_trajectory_score.h).
#include "trackbed/estimation/running_trajectory_score.h"

#include <cmath>

#include "trackbed/common/option_error.h"

namespace trackbed::estimation {

RunningTrajectoryScore::RunningTrajectoryScore(double segment_m) : segment_m_(segment_m) {
  option_check::Positive("segment_m", segment_m);
}

void RunningTrajectoryScore::Add(const Eigen::Isometry3d& T_world_body_true,
                                 const Eigen::Isometry3d& T_world_body_est) {
  const Eigen::Vector3d p_true = T_world_body_true.translation();
  const Eigen::Vector3d p_est = T_world_body_est.translation();
  // In the order of trajectory_metrics.cpp's sums, so these figures are bit for bit theirs.
  const Eigen::Vector2d horizontal = p_true.head<2>() - p_est.head<2>();
  horizontal_sq_sum_ += horizontal.squaredNorm();
  final_horizontal_m_ = horizontal.norm();
  if (count_ > 0) distance_m_ += (p_true - last_true_position_).norm();
  last_true_position_ = p_true;
  moments_.Add(p_est, p_true);
  ++count_;

  // Drift: a segment from pose i ends at the first pose whose true path length exceeds
  // that at i by segment_m (the devkit's lastFrameFromSegmentLength); segments complete in
  // the order of i, so the sum runs in the batch function's order.
  window_.push_back({distance_m_, T_world_body_true.matrix(), T_world_body_est.matrix()});
  const Pair& j = window_.back();
  while (window_.front().distance_m + segment_m_ < j.distance_m) {
    const Pair& i = window_.front();
    // E = (Q_i⁻¹ Q_j)⁻¹ (P_i⁻¹ P_j) with general 4×4 inverses, as RelativeError in
    // trajectory_metrics.cpp.
    const Eigen::Matrix4d E = (i.gt.inverse() * j.gt).inverse() * (i.est.inverse() * j.est);
    t_err_sum_ += E.block<3, 1>(0, 3).norm() / segment_m_;
    ++segments_;
    window_.pop_front();
  }
}

double RunningTrajectoryScore::horizontal_ate_rmse_m() const {
  if (count_ == 0) return 0.0;
  return std::sqrt(horizontal_sq_sum_ / static_cast<double>(count_));
}

double RunningTrajectoryScore::se3_ate_rmse_m() const {
  if (count_ == 0) return 0.0;
  const SimilarityTransform T = HornAbsoluteOrientationFromMoments(moments_, false);
  return std::sqrt(moments_.ResidualSquaredSum(T) / static_cast<double>(count_));
}

std::optional<double> RunningTrajectoryScore::rpe_trans_pct() const {
  if (segments_ == 0) return std::nullopt;
  return 100.0 * t_err_sum_ / static_cast<double>(segments_);
}

}  // namespace trackbed::estimation
