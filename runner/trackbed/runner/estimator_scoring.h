// Scores the localization stack's estimators, and estimators reported from outside
// the loop, against ground truth as a run goes (definitions: docs/run_folder.md):
// every estimate is paired with the true pose at the same simulation time, and added to
// running sums and a window of the last 10 m (estimation::RunningTrajectoryScore), so that
// the memory does not grow with the run's length.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "trackbed/estimation/pose_uncertainty.h"
#include "trackbed/estimation/running_trajectory_score.h"

namespace trackbed::runner {

struct EstimateSample;
struct ExternalEstimate;
struct LocalizationFrame;
struct RunSample;

/// The figures of one estimator (docs/run_folder.md).
struct EstimatorMetrics {
  double ate_rmse_m = 0.0;        ///< RMS horizontal error, no alignment.
  double ate3d_se3_rmse_m = 0.0;  ///< 3-D ATE after SE(3) alignment (evo-style).
  double final_error_m = 0.0;     ///< Horizontal error at the end.
  /// final_error_m / distance_m, in %; NaN (null in metrics.json) when the path is
  /// shorter than estimation::kMinPathForPerDistanceM.
  double final_error_pct = 0.0;
  /// Mean drift over 10 m of true path, % of 10 m; NaN (null in metrics.json) when the
  /// path is shorter than 10 m.
  double rpe_trans_pct = 0.0;
  long long samples = 0;
  /// Where the estimator's pose covariance comes from (`ekf_state`,
  /// `vo_frames_composed`, `covariance_fusion`), or `none`: it has no covariance of its
  /// own, and the fields below are NaN (null) and the flag false.
  std::string covariance = "none";
  /// Its own uncertainty passed the bound (estimation::LocalizationLostOptions) at some
  /// sample; the first such time [s], NaN when never.
  bool localization_lost = false;
  double localization_lost_time_s = 0.0;
  /// Its own uncertainty at the last sample (estimation::PoseUncertainty) [m, °]; +∞ when
  /// its covariance is not finite.
  double final_position_sigma_m = 0.0;
  double final_heading_sigma_deg = 0.0;
};

/// Visual odometry and fusion over a run.
struct LocalizationSummary {
  long long vo_frames = 0;
  long long vo_failures = 0;  ///< Frames with too few inliers (no motion).
  /// Frames whose motion is the constant-velocity prediction's consensus (RANSAC's broke
  /// the dynamics bounds).
  long long vo_dynamics_constrained = 0;
  /// Failed frames over which VO's pose went on at the last valid velocity.
  long long vo_coasted = 0;
  long long camera_blackout_frames = 0;  ///< Frames a camera fault blanked.
  double mean_inliers = 0.0;
  double mean_fusion_w = 0.0;           ///< Mean weight of wheel odometry.
  double slip_estimate_rmse_mps = 0.0;  ///< Estimated vs true slip velocity, both tracks.
};

class EstimatorScoring {
 public:
  /// `lost_bound`: when an estimator's own covariance says it is lost.
  explicit EstimatorScoring(const estimation::LocalizationLostOptions& lost_bound = {})
      : lost_bound_(lost_bound) {}

  void Add(const RunSample& truth, const EstimateSample& estimate);
  void AddFrame(const Eigen::Isometry3d& T_world_body_true, const LocalizationFrame& frame);
  /// An estimate from outside the loop, scored as its name's own track.
  void AddExternal(const ExternalEstimate& estimate);

  /// Metrics per estimator name (the stack's and those from outside); `distance_m` is
  /// the run's true path length.
  std::map<std::string, EstimatorMetrics> Metrics(double distance_m) const;
  LocalizationSummary Summary() const;
  bool empty() const { return wheel_.count() == 0; }
  /// Poses held in all the scores' drift windows (bounded by 10 m of path each).
  std::size_t window_size() const;

 private:
  using Running = estimation::RunningTrajectoryScore;
  Running wheel_, wheel_noslip_, fused_, ekf_, vo_;
  Running fused_ham2012_;  // scored when the samples carry it
  bool has_fused_ham2012_ = false;
  // One estimator's own uncertainty over the run, against the bound.
  struct Uncertainty {
    const char* source = nullptr;  // null: no covariance seen
    bool lost = false;
    double t_lost_s = 0.0;
    estimation::PoseUncertainty last;
    void Add(double t_s, const char* from, const std::optional<Eigen::Matrix3d>& P,
             const estimation::LocalizationLostOptions& bound);
  };
  // The figures of `score`, with `u`'s uncertainty (null: the estimator has none).
  static EstimatorMetrics Scored(const Running& score, const Uncertainty* u, double distance_m);
  estimation::LocalizationLostOptions lost_bound_;
  Uncertainty vo_uncertainty_, fused_uncertainty_, ekf_uncertainty_;
  std::map<std::string, Running> external_;  // name → its estimates against the truth then
  bool has_camera_ = false;
  long long vo_failures_ = 0, vo_constrained_ = 0, vo_coasted_ = 0, blackout_frames_ = 0;
  double inliers_sum_ = 0.0, w_sum_ = 0.0;
  double slip_sq_sum_ = 0.0;
  long long slip_samples_ = 0;
};

}  // namespace trackbed::runner
