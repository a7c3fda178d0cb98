// Scoring of the localization stack against ground truth (see estimator_scoring.h).
#include "trackbed/runner/estimator_scoring.h"

#include <cmath>
#include <limits>

#include "trackbed/estimation/per_distance.h"
#include "trackbed/estimation/trajectory_metrics.h"
#include "trackbed/runner/run_sample.h"

namespace trackbed::runner {

void EstimatorScoring::Add(const RunSample& truth, const EstimateSample& e) {
  truth_.push_back({truth.t_s, truth.chassis.T_world_body});
  wheel_.push_back({e.t_s, e.wheel_odometry});
  wheel_noslip_.push_back({e.t_s, e.wheel_odometry_noslip});
  ekf_.push_back({e.t_s, e.ekf});
  if (e.has_camera) {
    has_camera_ = true;
    fused_.push_back({e.t_s, e.fused});
  }
  for (int side = 0; side < 2; ++side) {
    const double estimated = side == 0 ? e.slip.left_mps : e.slip.right_mps;
    const double err = estimated - truth.tracks[side].slip_velocity_mps;
    slip_sq_sum_ += err * err;
    ++slip_samples_;
  }
}

void EstimatorScoring::AddFrame(const Eigen::Isometry3d& T_world_body_true,
                                const LocalizationFrame& frame) {
  vo_truth_.push_back({frame.t_s, T_world_body_true});
  vo_.push_back({frame.t_s, frame.visual_odometry});
  if (!frame.report.vo_valid) ++vo_failures_;
  if (frame.report.vo.dynamics_constrained) ++vo_constrained_;
  if (frame.report.vo_coasted) ++vo_coasted_;
  if (frame.camera_blackout) ++blackout_frames_;
  inliers_sum_ += frame.report.features;
  w_sum_ += frame.report.w;
}

void EstimatorScoring::AddExternal(const ExternalEstimate& e) {
  Track& track = external_[*e.name];
  track.truth.push_back({e.t_s, e.T_world_body_true});
  track.estimate.push_back({e.t_s, e.T_world_body});
}

namespace {

EstimatorMetrics Score(const estimation::Trajectory& gt, const estimation::Trajectory& est,
                       double distance_m) {
  EstimatorMetrics m;
  m.samples = static_cast<long long>(est.size());
  if (est.size() < 2) return m;
  m.ate_rmse_m = estimation::HorizontalAteRmse(gt, est);
  m.ate3d_se3_rmse_m =
      estimation::AbsoluteTrajectoryError(gt, est, estimation::AlignmentMode::kSe3).error_m.rmse;
  m.final_error_m = estimation::ComputeFinalError(gt, est).horizontal_m;
  m.final_error_pct = estimation::PercentOfPath(m.final_error_m, distance_m);
  m.rpe_trans_pct =
      estimation::RpeTransPct(gt, est).value_or(std::numeric_limits<double>::quiet_NaN());
  return m;
}

}  // namespace

std::map<std::string, EstimatorMetrics> EstimatorScoring::Metrics(double distance_m) const {
  std::map<std::string, EstimatorMetrics> m;
  for (const auto& [name, track] : external_)
    m[name] = Score(track.truth, track.estimate, distance_m);
  if (truth_.empty()) return m;
  m["wheel_odometry"] = Score(truth_, wheel_, distance_m);
  m["wheel_odometry_noslip"] = Score(truth_, wheel_noslip_, distance_m);
  m["ekf"] = Score(truth_, ekf_, distance_m);
  if (has_camera_) {
    m["fused"] = Score(truth_, fused_, distance_m);
    m["visual_odometry"] = Score(vo_truth_, vo_, distance_m);
  }
  return m;
}

LocalizationSummary EstimatorScoring::Summary() const {
  LocalizationSummary s;
  s.vo_frames = static_cast<long long>(vo_.size());
  s.vo_failures = vo_failures_;
  s.vo_dynamics_constrained = vo_constrained_;
  s.vo_coasted = vo_coasted_;
  s.camera_blackout_frames = blackout_frames_;
  if (!vo_.empty()) {
    s.mean_inliers = inliers_sum_ / static_cast<double>(vo_.size());
    s.mean_fusion_w = w_sum_ / static_cast<double>(vo_.size());
  }
  if (slip_samples_ > 0) s.slip_estimate_rmse_mps = std::sqrt(slip_sq_sum_ / slip_samples_);
  return s;
}

}  // namespace trackbed::runner
