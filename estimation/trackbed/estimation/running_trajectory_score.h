// The run folder's figures of one estimate (docs/run_folder.md, `estimators.<name>`)
// accumulated pose by pose, in memory that does not grow with the run's length: the
// horizontal ATE and the final error from running sums, the SE(3)-aligned ATE from the
// positions' moments (Horn's alignment is exact from them), and the drift over 10 m from
// a window of the poses of the last 10 m of true path. Each figure equals the one the
// functions of trajectory_metrics.h give on the whole associated trajectories, the aligned
// ATE up to floating-point rounding (docs/localization.md, "Scoring as the run goes").
#pragma once

#include <cstddef>
#include <deque>
#include <optional>

#include <Eigen/Geometry>

#include "trackbed/estimation/absolute_orientation.h"

namespace trackbed::estimation {

class RunningTrajectoryScore {
 public:
  /// `segment_m`: the drift's segment of true path [m] (> 0; rpe_trans_pct's 10 m).
  explicit RunningTrajectoryScore(double segment_m = 10.0);

  /// One associated pair: the true pose and the estimate at the same instant.
  void Add(const Eigen::Isometry3d& T_world_body_true, const Eigen::Isometry3d& T_world_body_est);

  long long count() const { return count_; }
  /// HorizontalAteRmse of the pairs so far (0 when empty).
  double horizontal_ate_rmse_m() const;
  /// AbsoluteTrajectoryError(kSe3).error_m.rmse of the pairs so far (0 when empty).
  double se3_ate_rmse_m() const;
  /// ComputeFinalError(...).horizontal_m at the last pair (0 when empty).
  double final_horizontal_error_m() const { return final_horizontal_m_; }
  /// PathLength of the true poses so far [m].
  double true_path_length_m() const { return distance_m_; }
  /// RpeTransPct of the pairs so far: std::nullopt while no segment is complete.
  std::optional<double> rpe_trans_pct() const;

  /// Poses held for the drift's open segments: those of the last `segment_m` of true path
  /// (a robot standing still adds one per pair until it moves on).
  std::size_t window_size() const { return window_.size(); }

 private:
  struct Pair {
    double distance_m;  // true path length at this pose
    Eigen::Matrix4d gt, est;
  };
  double segment_m_;
  long long count_ = 0;
  double horizontal_sq_sum_ = 0.0;
  PointPairMoments moments_;  // est → gt positions
  double final_horizontal_m_ = 0.0;
  double distance_m_ = 0.0;
  Eigen::Vector3d last_true_position_ = Eigen::Vector3d::Zero();
  std::deque<Pair> window_;
  double t_err_sum_ = 0.0;
  long long segments_ = 0;
};

}  // namespace trackbed::estimation
