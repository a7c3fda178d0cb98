// Scoring of the localization stack against ground truth (see estimator_scoring.h).
#include "trackbed/runner/estimator_scoring.h"

#include <cmath>
#include <limits>

#include "trackbed/estimation/per_distance.h"
#include "trackbed/runner/run_sample.h"

namespace trackbed::runner {

void EstimatorScoring::Add(const RunSample& truth, const EstimateSample& e) {
  const Eigen::Isometry3d& T_true = truth.chassis.T_world_body;
  wheel_.Add(T_true, e.wheel_odometry);
  wheel_noslip_.Add(T_true, e.wheel_odometry_noslip);
  ekf_.Add(T_true, e.ekf);
  if (e.has_camera) {
    has_camera_ = true;
    fused_.Add(T_true, e.fused);
  }
  if (e.fused_ham2012) {
    has_fused_ham2012_ = true;
    fused_ham2012_.Add(T_true, *e.fused_ham2012);
  }
  vo_uncertainty_.Add(e.t_s, "vo_frames_composed", e.covariances.visual_odometry, lost_bound_);
  fused_uncertainty_.Add(e.t_s, "covariance_fusion", e.covariances.fused, lost_bound_);
  ekf_uncertainty_.Add(e.t_s, "ekf_state", e.covariances.ekf, lost_bound_);
  for (int side = 0; side < 2; ++side) {
    const double estimated = side == 0 ? e.slip.left_mps : e.slip.right_mps;
    const double err = estimated - truth.tracks[side].slip_velocity_mps;
    slip_sq_sum_ += err * err;
    ++slip_samples_;
  }
}

void EstimatorScoring::Uncertainty::Add(double t_s, const char* from,
                                        const std::optional<Eigen::Matrix3d>& P,
                                        const estimation::LocalizationLostOptions& bound) {
  if (!P) return;
  source = from;
  last = estimation::UncertaintyOf(*P);
  if (!lost && estimation::BeyondBound(last, bound)) {
    lost = true;
    t_lost_s = t_s;
  }
}

void EstimatorScoring::AddFrame(const Eigen::Isometry3d& T_world_body_true,
                                const LocalizationFrame& frame) {
  vo_.Add(T_world_body_true, frame.visual_odometry);
  if (!frame.report.vo_valid) ++vo_failures_;
  if (frame.report.vo.dynamics_constrained) ++vo_constrained_;
  if (frame.report.vo_coasted) ++vo_coasted_;
  if (frame.camera_blackout) ++blackout_frames_;
  inliers_sum_ += frame.report.features;
  w_sum_ += frame.report.w;
}

void EstimatorScoring::AddExternal(const ExternalEstimate& e) {
  external_[*e.name].Add(e.T_world_body_true, e.T_world_body);
}

std::size_t EstimatorScoring::window_size() const {
  std::size_t n = 0;
  for (const Running* s : {&wheel_, &wheel_noslip_, &fused_, &ekf_, &vo_, &fused_ham2012_}) {
    n += s->window_size();
  }
  for (const auto& [name, s] : external_) n += s.window_size();
  return n;
}

namespace {

// The figures of one estimate from its running score (the same as the batch functions of
// trajectory_metrics.h on the whole trajectories; the aligned ATE up to rounding).
EstimatorMetrics Score(const estimation::RunningTrajectoryScore& score, double distance_m) {
  EstimatorMetrics m;
  m.samples = score.count();
  if (score.count() < 2) return m;
  m.ate_rmse_m = score.horizontal_ate_rmse_m();
  m.ate3d_se3_rmse_m = score.se3_ate_rmse_m();
  m.final_error_m = score.final_horizontal_error_m();
  m.final_error_pct = estimation::PercentOfPath(m.final_error_m, distance_m);
  m.rpe_trans_pct = score.rpe_trans_pct().value_or(std::numeric_limits<double>::quiet_NaN());
  return m;
}

// `m` with an estimator's own uncertainty over the run.
EstimatorMetrics WithUncertainty(EstimatorMetrics m, const char* source, bool lost, double t_lost_s,
                                 const estimation::PoseUncertainty& last) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  m.localization_lost_time_s = kNaN;
  m.final_position_sigma_m = kNaN;
  m.final_heading_sigma_deg = kNaN;
  if (!source) return m;
  m.covariance = source;
  m.localization_lost = lost;
  if (lost) m.localization_lost_time_s = t_lost_s;
  m.final_position_sigma_m = last.position_sigma_m;
  m.final_heading_sigma_deg = last.heading_sigma_rad * 180.0 / M_PI;
  return m;
}

}  // namespace

EstimatorMetrics EstimatorScoring::Scored(const Running& score, const Uncertainty* u,
                                          double distance_m) {
  if (!u) return WithUncertainty(Score(score, distance_m), nullptr, false, 0.0, {});
  return WithUncertainty(Score(score, distance_m), u->source, u->lost, u->t_lost_s, u->last);
}

std::map<std::string, EstimatorMetrics> EstimatorScoring::Metrics(double distance_m) const {
  std::map<std::string, EstimatorMetrics> m;
  for (const auto& [name, score] : external_) m[name] = Scored(score, nullptr, distance_m);
  if (empty()) return m;
  m["wheel_odometry"] = Scored(wheel_, nullptr, distance_m);
  m["wheel_odometry_noslip"] = Scored(wheel_noslip_, nullptr, distance_m);
  m["ekf"] = Scored(ekf_, &ekf_uncertainty_, distance_m);
  if (has_camera_) {
    m["fused"] = Scored(fused_, &fused_uncertainty_, distance_m);
    m["visual_odometry"] = Scored(vo_, &vo_uncertainty_, distance_m);
  }
  if (has_fused_ham2012_) m["fused_ham2012"] = Scored(fused_ham2012_, nullptr, distance_m);
  return m;
}

LocalizationSummary EstimatorScoring::Summary() const {
  LocalizationSummary s;
  s.vo_frames = vo_.count();
  s.vo_failures = vo_failures_;
  s.vo_dynamics_constrained = vo_constrained_;
  s.vo_coasted = vo_coasted_;
  s.camera_blackout_frames = blackout_frames_;
  if (vo_.count() > 0) {
    s.mean_inliers = inliers_sum_ / static_cast<double>(vo_.count());
    s.mean_fusion_w = w_sum_ / static_cast<double>(vo_.count());
  }
  if (slip_samples_ > 0) s.slip_estimate_rmse_mps = std::sqrt(slip_sq_sum_ / slip_samples_);
  return s;
}

}  // namespace trackbed::runner
