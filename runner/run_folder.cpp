// Run folder writer (see run_folder.h).
#include "trackbed/runner/run_folder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "trackbed/common/durable_file.h"
#include "trackbed/estimation/per_distance.h"
#include "trackbed/estimation/trajectory.h"
#include "trackbed/estimation/trajectory_metrics.h"
#include "trackbed/perception/kitti_sequence.h"
#include "trackbed/perception/opencv_views.h"
#include "trackbed/perception/stereo_rectifier.h"
#include "trackbed/plot/plots.h"
#include "trackbed/runner/camera_frame_log.h"
#include "trackbed/runner/input_files.h"
#include "trackbed/runner/log_file.h"
#include "trackbed/runner/navigation_log.h"
#include "trackbed/runner/navigation_scenario.h"
#include "trackbed/runner/plot_decimation.h"
#include "trackbed/runner/run_bag.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {
namespace {

using Json = nlohmann::ordered_json;

// A figure, or null where it is n/a (NaN).
nlohmann::ordered_json FiniteOrNull(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json();
}

namespace fs = std::filesystem;

// The means are null over no sample (a run that never moved, kinematic navigation).
nlohmann::ordered_json SlipJson(const SlipStats& s) {
  const auto mean = [&s](double v) { return s.samples ? nlohmann::ordered_json(v) : nullptr; };
  nlohmann::ordered_json j;
  j["mean_abs_slip_ratio"] = mean(s.mean_abs_ratio());
  j["mean_slip_ratio"] = mean(s.mean_ratio());
  j["mean_abs_slip_velocity_mps"] = mean(s.mean_abs_velocity_mps());
  j["samples"] = s.samples;
  return j;
}

// What the plots need, gathered at 10 Hz while the run goes, decimated to a bounded size
// (plot_decimation.h).
struct PlotData {
  DecimatedPath truth;
  std::map<std::string, DecimatedPath> estimates;  // name → poses
  DecimatedSeries w, slip_left_true, slip_left_est, slip_right_true, slip_right_est;

  void Add(const RunSample& s) {
    if (std::lround(s.t_s * 100.0) % 10 != 0) return;  // every 0.1 s
    truth.Add(s.t_s, s.chassis.T_world_body);
    if (!s.estimate) return;
    const EstimateSample& e = *s.estimate;
    estimates["wheel_odometry"].Add(s.t_s, e.wheel_odometry);
    estimates["wheel_odometry_noslip"].Add(s.t_s, e.wheel_odometry_noslip);
    estimates["ekf"].Add(s.t_s, e.ekf);
    if (e.has_camera) estimates["fused"].Add(s.t_s, e.fused);
    if (e.fused_ham2012) estimates["fused_ham2012"].Add(s.t_s, *e.fused_ham2012);
    slip_left_true.Add(s.t_s, s.tracks[0].slip_velocity_mps);
    slip_right_true.Add(s.t_s, s.tracks[1].slip_velocity_mps);
    slip_left_est.Add(s.t_s, e.slip.left_mps);
    slip_right_est.Add(s.t_s, e.slip.right_mps);
  }

  // The sizes of every path and series.
  std::vector<std::size_t> Sizes() const {
    std::vector<std::size_t> n{truth.size(),           w.size(),
                               slip_left_true.size(),  slip_left_est.size(),
                               slip_right_true.size(), slip_right_est.size()};
    for (const auto& [name, t] : estimates) n.push_back(t.size());
    return n;
  }

  // trajectories.png, error_histogram.png and (with a camera) fusion.png.
  void Write(const fs::path& dir, const std::string& scene) const {
    if (truth.Points().size() < 2 || estimates.empty()) return;
    std::vector<plot::PlotSeries> paths{{"ground truth", truth.Points()}};
    for (const auto& [name, t] : estimates) paths.push_back({name, t.Points()});
    plot::WriteTrajectoryPlot(dir / "trajectories.png", scene + ": trajectories over the true path",
                              paths);
    std::vector<double> edges;
    for (int k = 0; k <= 20; ++k) edges.push_back(0.05 * k);
    std::vector<plot::HistogramSeries> bars;
    const estimation::Trajectory truth_poses = truth.Poses();
    for (const auto& [name, t] : estimates) {
      const estimation::DistanceHistogram h =
          estimation::DistanceErrorHistogram(t.Poses(), truth_poses, edges);
      plot::HistogramSeries b{name + " (>1 m: " + std::to_string(h.above) + ")", {}};
      for (std::size_t c : h.counts) b.counts.push_back(static_cast<double>(c) / h.total());
      bars.push_back(b);
    }
    plot::WriteHistogramPlot(dir / "error_histogram.png",
                             scene + ": distance of each estimate to the true path",
                             "distance to the true path [m]", edges, bars, /*first_color=*/1);
    if (w.empty()) return;
    plot::WriteTimePlot(
        dir / "fusion.png", scene + ": fusion weight and track slip",
        {{"w (wheel odometry)", {{"w", w.points()}}},
         {"left slip [m/s]",
          {{"true", slip_left_true.points()}, {"estimated", slip_left_est.points()}}},
         {"right slip [m/s]",
          {{"true", slip_right_true.points()}, {"estimated", slip_right_est.points()}}}});
  }
};

// The header of `pose_covariance.csv`: the estimators that have a covariance in this run.
std::string PoseCovarianceHeader(const scenario::Scenario& scenario) {
  std::string header = "t";
  const auto add = [&header](const char* name) {
    for (const char* c : {"xx_m2", "xy_m2", "xyaw_m_rad", "yy_m2", "yyaw_m_rad", "yawyaw_rad2"}) {
      header += std::string(",") + name + "_" + c;
    }
  };
  if (scenario.robot.stereo.enabled) {
    add("visual_odometry");
    if (scenario.estimation.localization.fusion.method ==
        estimation::FusionOptions::Method::kCovariance) {
      add("fused");
    }
  }
  add("ekf");
  return header;
}

// The run's logs, one file each with its header (README.md, "Run folder"): ground
// truth, encoders, slip, tracks, IMU, twist, and one TUM file per estimator when
// estimation is on.
class RunLogs {
 public:
  RunLogs(const fs::path& dir, const scenario::Scenario& scenario)
      : truth_(dir / "ground_truth.tum", ""),
        encoders_(dir / "encoders.csv", "t,left_ticks,right_ticks"),
        slip_(dir / "slip.csv",
              "t,left_true_mps,right_true_mps,left_track_mps,right_track_mps,"
              "left_ground_mps,right_ground_mps,material,left_est_mps,right_est_mps"),
        tracks_(dir / "tracks.csv",
                "t,left_torque_nm,right_torque_nm,left_load_n,right_load_n,"
                "left_traction_n,right_traction_n,left_compaction_n,right_compaction_n,"
                "left_contacts,right_contacts"),
        imu_(dir / "imu.csv",
             "t,gyro_x_radps,gyro_y_radps,gyro_z_radps,accel_x_mps2,accel_y_mps2,accel_z_mps2"),
        twist_(dir / "ground_truth_twist.csv",
               "t,v_x_mps,v_y_mps,v_z_mps,omega_x_radps,omega_y_radps,omega_z_radps"),
        decimate_(scenario.outputs.decimate) {
    if (scenario.robot.range_sensor.enabled) {
      std::string header = "t";
      for (int k = 0; k < scenario.robot.range_sensor.beams; ++k)
        header += ",range_" + std::to_string(k) + "_m";
      scan_csv_ = std::make_unique<LogFile>(dir / "scan.csv", header);
    }
    if (!scenario.estimation.enabled) return;
    wheel_tum_ = std::make_unique<LogFile>(dir / "wheel_odometry.tum", "");
    noslip_tum_ = std::make_unique<LogFile>(dir / "wheel_odometry_noslip.tum", "");
    ekf_tum_ = std::make_unique<LogFile>(dir / "ekf.tum", "");
    pose_covariance_csv_ =
        std::make_unique<LogFile>(dir / "pose_covariance.csv", PoseCovarianceHeader(scenario));
    if (!scenario.robot.stereo.enabled) return;
    fused_tum_ = std::make_unique<LogFile>(dir / "fused.tum", "");
    vo_tum_ = std::make_unique<LogFile>(dir / "visual_odometry.tum", "");
    if (scenario.estimation.localization.fusion.method ==
        estimation::FusionOptions::Method::kCovariance) {
      fused_ham2012_tum_ = std::make_unique<LogFile>(dir / "fused_ham2012.tum", "");
    }
    fusion_csv_ = std::make_unique<LogFile>(
        dir / "fusion.csv",
        "t,slip_velocity_mps,features,w,vo_status,vo_tracked,camera_blackout,w_rule,"
        "vo_dynamics_constrained");
    std::string header = "t,vo_status,x_m,y_m,z_m,rx_rad,ry_rad,rz_rad,image_noise_px";
    for (int i = 0; i < 6; ++i) {
      for (int j = i; j < 6; ++j) header += ",c" + std::to_string(i) + std::to_string(j);
    }
    vo_covariance_csv_ = std::make_unique<LogFile>(dir / "vo_covariance.csv", header);
  }

  // Every sample; the logs keep every decimate-th (outputs.decimate).
  void Sample(const RunSample& s) {
    if (samples_++ % decimate_ == 0) WriteSample(s);
  }
  void Imu(const robot::ImuSample& s) {
    if (imu_samples_++ % decimate_ == 0) WriteImu(s);
  }
  void Frame(const LocalizationFrame& f);
  void Scan(const robot::RangeScanSample& s);
  // An estimate reported from outside the loop: a line of `<name>.tum`.
  void External(const fs::path& dir, const ExternalEstimate& e) {
    std::unique_ptr<LogFile>& tum = external_tum_[*e.name];
    if (!tum) tum = std::make_unique<LogFile>(dir / (*e.name + ".tum"), "");
    tum->Line(estimation::FormatTumLine({e.t_s, e.T_world_body}).c_str());
  }
  void Close() {
    for (LogFile* f : {&truth_, &twist_, &encoders_, &slip_, &tracks_, &imu_}) f->Close();
    for (auto* f : {&wheel_tum_, &noslip_tum_, &ekf_tum_, &fused_tum_, &vo_tum_, &fusion_csv_,
                    &scan_csv_, &vo_covariance_csv_, &fused_ham2012_tum_, &pose_covariance_csv_}) {
      if (*f) (*f)->Close();
    }
    for (auto& [name, f] : external_tum_) f->Close();
  }

 private:
  LogFile truth_, encoders_, slip_, tracks_, imu_, twist_;
  std::unique_ptr<LogFile> wheel_tum_, noslip_tum_, ekf_tum_, fused_tum_, vo_tum_, fusion_csv_,
      scan_csv_, vo_covariance_csv_, fused_ham2012_tum_, pose_covariance_csv_;
  std::map<std::string, std::unique_ptr<LogFile>> external_tum_;  // reported estimators
  long long decimate_ = 1, samples_ = 0, imu_samples_ = 0;
  char line_[512];
  void WriteSample(const RunSample& s);
  void WriteImu(const robot::ImuSample& s);
  void WriteVoCovariance(const LocalizationFrame& f);
  void WritePoseCovariance(const EstimateSample& e);
};

void RunLogs::WriteSample(const RunSample& s) {
  truth_.Line(estimation::FormatTumLine({s.t_s, s.chassis.T_world_body}).c_str());
  std::snprintf(line_, sizeof(line_), "%.6f,%lld,%lld", s.t_s, s.ticks[0], s.ticks[1]);
  encoders_.Line(line_);
  const robot::TrackState &l = s.tracks[0], &r = s.tracks[1];
  const int n =
      std::snprintf(line_, sizeof(line_), "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%s,", s.t_s,
                    l.slip_velocity_mps, r.slip_velocity_mps, l.track_speed_mps, r.track_speed_mps,
                    l.ground_speed_mps, r.ground_speed_mps, s.material ? s.material->c_str() : "");
  const std::size_t used = static_cast<std::size_t>(n);
  if (s.estimate) {
    std::snprintf(line_ + used, sizeof(line_) - used, "%.9g,%.9g", s.estimate->slip.left_mps,
                  s.estimate->slip.right_mps);
  } else {
    std::snprintf(line_ + used, sizeof(line_) - used, ",");
  }
  slip_.Line(line_);
  if (s.estimate) {
    wheel_tum_->Line(estimation::FormatTumLine({s.t_s, s.estimate->wheel_odometry}).c_str());
    noslip_tum_->Line(
        estimation::FormatTumLine({s.t_s, s.estimate->wheel_odometry_noslip}).c_str());
    ekf_tum_->Line(estimation::FormatTumLine({s.t_s, s.estimate->ekf}).c_str());
    if (fused_tum_) {
      fused_tum_->Line(estimation::FormatTumLine({s.t_s, s.estimate->fused}).c_str());
    }
    if (fused_ham2012_tum_ && s.estimate->fused_ham2012) {
      fused_ham2012_tum_->Line(
          estimation::FormatTumLine({s.t_s, *s.estimate->fused_ham2012}).c_str());
    }
    WritePoseCovariance(*s.estimate);
  }
  std::snprintf(line_, sizeof(line_), "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%d", s.t_s,
                l.motor_torque_nm, r.motor_torque_nm, l.normal_load_n, r.normal_load_n,
                l.traction_n, r.traction_n, l.compaction_resistance_n, r.compaction_resistance_n,
                l.stations_in_contact, r.stations_in_contact);
  tracks_.Line(line_);
  // Body-frame twist: velocity of the body origin and angular velocity, in body axes.
  const Eigen::Matrix3d R_body_world = s.chassis.T_world_body.linear().transpose();
  const Eigen::Vector3d v = R_body_world * s.chassis.v_world;
  const Eigen::Vector3d w = R_body_world * s.chassis.omega_world;
  std::snprintf(line_, sizeof(line_), "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", s.t_s, v.x(), v.y(),
                v.z(), w.x(), w.y(), w.z());
  twist_.Line(line_);
}

void RunLogs::Frame(const LocalizationFrame& f) {
  if (!vo_tum_) return;
  vo_tum_->Line(estimation::FormatTumLine({f.t_s, f.visual_odometry}).c_str());
  std::snprintf(line_, sizeof(line_), "%.6f,%.9g,%.0f,%.6f,%s,%d,%d,%.6f,%d", f.t_s,
                f.report.slip_velocity_mps, f.report.features, f.report.w,
                estimation::ToString(f.report.vo.status), f.report.vo.tracked,
                f.camera_blackout ? 1 : 0, f.report.w_rule,
                f.report.vo.dynamics_constrained ? 1 : 0);
  fusion_csv_->Line(line_);
  WriteVoCovariance(f);
}

// VO's body motion and its covariance (docs/run_folder.md, `vo_covariance.csv`); the
// numbers empty on a frame without a motion.
void RunLogs::WriteVoCovariance(const LocalizationFrame& f) {
  std::string row(
      line_, static_cast<std::size_t>(std::snprintf(line_, sizeof(line_), "%.6f,%s", f.t_s,
                                                    estimation::ToString(f.report.vo.status))));
  if (!f.report.vo_valid || !f.report.vo.covariance_valid) {
    row += ",,,,,,,";
    for (int k = 0; k < 21; ++k) row += ',';
    vo_covariance_csv_->Line(row.c_str());
    return;
  }
  const Eigen::Isometry3d& M = f.report.vo_body_motion;
  const Eigen::AngleAxisd aa(M.linear());
  const Eigen::Vector3d r = aa.angle() * aa.axis();
  std::snprintf(line_, sizeof(line_), ",%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g", M.translation().x(),
                M.translation().y(), M.translation().z(), r.x(), r.y(), r.z(),
                f.report.vo.image_noise_px);
  row += line_;
  for (int i = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) {
      std::snprintf(line_, sizeof(line_), ",%.6g", f.report.vo_body_covariance(i, j));
      row += line_;
    }
  }
  vo_covariance_csv_->Line(row.c_str());
}

// Each estimator's pose covariance that has one, in the header's order
// (docs/run_folder.md, `pose_covariance.csv`).
void RunLogs::WritePoseCovariance(const EstimateSample& e) {
  std::string row(line_,
                  static_cast<std::size_t>(std::snprintf(line_, sizeof(line_), "%.6f", e.t_s)));
  for (const std::optional<Eigen::Matrix3d>* P :
       {&e.covariances.visual_odometry, &e.covariances.fused, &e.covariances.ekf}) {
    if (!*P) continue;
    for (int i = 0; i < 3; ++i) {
      for (int j = i; j < 3; ++j) {
        std::snprintf(line_, sizeof(line_), ",%.6g", (**P)(i, j));
        row += line_;
      }
    }
  }
  pose_covariance_csv_->Line(row.c_str());
}

void RunLogs::WriteImu(const robot::ImuSample& s) {
  std::snprintf(line_, sizeof(line_), "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", s.t_s, s.gyro_radps.x(),
                s.gyro_radps.y(), s.gyro_radps.z(), s.accel_mps2.x(), s.accel_mps2.y(),
                s.accel_mps2.z());
  imu_.Line(line_);
}

// A scan's ranges in beam order, `inf` where no return.
void RunLogs::Scan(const robot::RangeScanSample& s) {
  std::string row(line_,
                  static_cast<std::size_t>(std::snprintf(line_, sizeof(line_), "%.6f", s.t_s)));
  for (double r : s.ranges_m) {
    row += ',';
    row.append(line_, static_cast<std::size_t>(std::snprintf(line_, sizeof(line_), "%.7g", r)));
  }
  scan_csv_->Line(row.c_str());
}

// The track marks' figures (scene.appearance.track_marks): their record's bound under
// memory, the points under track_marks.
void AddTrackMarks(const RunMetrics::TrackMarkCounts& t, Json* j) {
  (*j)["memory"]["track_marks_bound_mb"] = t.bound_mb;
  (*j)["track_marks"] = {{"points_held", t.points_held}, {"points_recorded", t.points_recorded}};
}

}  // namespace

std::string MetricsJson(const RunMetrics& m) {
  nlohmann::ordered_json j;
  j["status"] = m.completed ? "completed" : "failed";
  j["stop_reason"] = m.stop_reason;
  j["sim_time_s"] = m.sim_time_s;
  j["wall_time_s"] = m.wall_time_s;
  j["real_time_factor"] = m.real_time_factor();
  j["distance_m"] = m.distance_m;
  j["encoder_distance_m"] = m.encoder_distance_m;
  j["encoder_distance_error_pct"] =
      FiniteOrNull(estimation::PercentOfPath(m.encoder_distance_m - m.distance_m, m.distance_m));
  j["min_com_height_m"] = m.min_com_height_m;
  nlohmann::ordered_json slip;
  slip["left"] = SlipJson(m.slip[robot::kLeft]);
  slip["right"] = SlipJson(m.slip[robot::kRight]);
  nlohmann::ordered_json by_material = nlohmann::ordered_json::object();
  for (const auto& [name, stats] : m.slip_by_material) by_material[name] = SlipJson(stats);
  slip["by_material"] = by_material;
  j["slip"] = slip;
  // χ only where the run identifies it (docs/physics.md, "ICR calibration").
  j["icr_expansion"] = {
      {"chi", m.icr.identified ? nlohmann::ordered_json(m.icr.chi) : nlohmann::ordered_json()},
      {"samples", m.icr.samples_used},
      {"rms_residual_radps", m.icr.rms_residual_radps},
      {"chi_stderr", FiniteOrNull(m.icr.chi_stderr)},
      {"turn_rms_radps", m.icr.turn_rms_radps},
      {"identified", m.icr.identified},
      {"reason", m.icr.reason}};
  j["stereo_frames"] = m.stereo_frames;
  nlohmann::ordered_json estimators = nlohmann::ordered_json::object();
  for (const auto& [name, e] : m.estimators) {
    estimators[name] = {{"ate_rmse_m", e.ate_rmse_m},
                        {"ate3d_se3_rmse_m", e.ate3d_se3_rmse_m},
                        {"final_error_m", e.final_error_m},
                        {"final_error_pct", FiniteOrNull(e.final_error_pct)},
                        {"rpe_trans_pct", FiniteOrNull(e.rpe_trans_pct)},
                        {"samples", e.samples},
                        {"covariance", e.covariance}};
    // The estimator's own uncertainty against the bound: null without a covariance; a
    // sigma null also where it is not finite (the flag then says lost).
    const bool has = e.covariance != "none";
    estimators[name]["localization_lost"] = has ? Json(e.localization_lost) : nullptr;
    estimators[name]["localization_lost_time_s"] = FiniteOrNull(e.localization_lost_time_s);
    estimators[name]["final_position_sigma_m"] = FiniteOrNull(e.final_position_sigma_m);
    estimators[name]["final_heading_sigma_deg"] = FiniteOrNull(e.final_heading_sigma_deg);
  }
  j["estimators"] = estimators;
  const LocalizationSummary& loc = m.localization;
  j["localization"] = {
      {"vo_frames", loc.vo_frames},
      {"camera_blackout_frames", loc.camera_blackout_frames},
      {"vo_failures", loc.vo_failures},
      {"vo_dynamics_constrained", loc.vo_dynamics_constrained},
      {"vo_coasted", loc.vo_coasted},
      // Means over no frame, or no wheel-odometry sample, are null.
      {"mean_inliers", loc.vo_frames ? Json(loc.mean_inliers) : nullptr},
      {"mean_fusion_w", loc.vo_frames ? Json(loc.mean_fusion_w) : nullptr},
      {"slip_estimate_rmse_mps",
       m.estimators.count("wheel_odometry") ? Json(loc.slip_estimate_rmse_mps) : nullptr}};
  j["timing"] = {{"render_s", m.render_wall_s},
                 {"sensor_model_s", m.sensor_model_wall_s},
                 {"estimation_s", m.estimation_wall_s},
                 {"physics_s", m.physics_wall_s},
                 {"control_s", m.control_wall_s},
                 {"sensing_s", m.sensing_wall_s},
                 {"io_s", m.io_wall_s},
                 {"setup_s", m.setup_wall_s}};
  j["memory"] = {{"peak_rss_mb", m.peak_rss_mb}};
  if (m.track_marks) AddTrackMarks(*m.track_marks, &j);
  if (m.teach_repeat) {
    const TeachRepeatMetrics& t = *m.teach_repeat;
    j["teach_repeat"] = {{"method", t.method},
                         {"status", t.status},
                         {"completed", t.completed},
                         {"autonomy", t.autonomy},
                         {"end_point_error_m", t.end_point_error_m},
                         {"lateral_rms_m", t.lateral_rms_m},
                         {"lateral_max_m", t.lateral_max_m},
                         {"lateral_start_m", t.lateral_start_m},
                         {"lateral_end_rms_m", t.lateral_end_rms_m},
                         {"taught_length_m", t.taught_length_m},
                         {"features_lost", t.features_lost},
                         {"features_recovered", t.features_recovered},
                         {"recovery_rate", FiniteOrNull(t.recovery_rate)},
                         {"recovery_rate_pooled", FiniteOrNull(t.recovery_rate_pooled)},
                         {"milestones", t.milestones},
                         {"teach_images", t.teach_images},
                         {"switches_by_distance", t.switches_by_distance},
                         {"map_size_mb", t.map_size_mb},
                         {"map_mb_per_100m", FiniteOrNull(t.map_mb_per_100m)}};
    nlohmann::ordered_json places = nlohmann::ordered_json::array();
    for (const TeachRepeatMetrics::Place& p : t.places) {
      places.push_back({{"start_s", p.start_s},
                        {"end_s", p.end_s},
                        {"lost", p.lost},
                        {"recovered", p.recovered},
                        {"rate", FiniteOrNull(p.rate)}});
    }
    j["teach_repeat"]["places"] = places;
  }
  if (m.navigation) {
    const navigation::NavigationMetrics& n = *m.navigation;
    j["navigation"] = {
        {"method", m.navigation_method},
        {"success", n.success},
        {"status", n.status},
        {"time_to_goal_s",
         n.time_to_goal_s ? nlohmann::ordered_json(*n.time_to_goal_s) : nlohmann::ordered_json()},
        {"duration_s", n.duration_s},
        {"path_length_m", n.path_length_m},
        {"final_position_error_m", n.final_position_error_m},
        {"final_heading_error_deg", n.final_heading_error_deg},
        {"min_clearance_m", FiniteOrNull(n.min_clearance_m)},
        {"mean_clearance_m", FiniteOrNull(n.mean_clearance_m)},
        {"collisions", n.collisions},
        {"integrated_abs_jerk", n.integrated_abs_jerk},
        {"subgoals", n.subgoals}};
  }
  return j.dump(2) + "\n";
}

void WriteMetricsJson(const RunMetrics& metrics, const fs::path& dir) {
  // Everything the run wrote is on disk before metrics.json says it finished.
  SyncFolder(dir);
  WriteFileAtomically(dir / "metrics.json", MetricsJson(metrics));
}

// Everything the folder holds besides metrics.json, opened at the start.
struct RunFolderWriter::Files {
  Files(const fs::path& dir, const scenario::Scenario& scenario) : logs(dir, scenario) {}
  RunLogs logs;
  PlotData plots;
  std::unique_ptr<perception::StereoRectifier> rectifier;         // with kitti
  Eigen::Isometry3d T_left_rect = Eigen::Isometry3d::Identity();  // its rotation
  std::unique_ptr<perception::KittiWriter> kitti;
  Eigen::Isometry3d T_world_cam0 = Eigen::Isometry3d::Identity();
  std::unique_ptr<LogFile> navigation_csv;
  StrideDecimated<navigation::NavigationLogEntry> navigation_log;  // for navigation.png
  std::unique_ptr<LogFile> exposure_csv;                           // with the auto-exposure
  std::unique_ptr<CameraFrameLog> camera;                          // with outputs.mcap_images
};

RunFolderWriter::RunFolderWriter(const scenario::Scenario& scenario, const fs::path& dir)
    : dir_(dir) {
  fs::create_directories(dir);
  fs::remove(dir / "metrics.json");  // no stale result may pass for this run's
  WriteFileAtomically(dir / "scenario.yaml",
                      scenario::ScenarioToYaml(scenario::WithBuiltinMaterialsResolved(
                          scenario::WithRealismResolved(scenario))));
  WriteInputsJson(scenario, dir);
  WriteUnmapped(scenario, dir);
  files_ = std::make_unique<Files>(dir, scenario);
  if (scenario.navigation.enabled) {
    files_->navigation_csv =
        std::make_unique<LogFile>(dir / "navigation.csv", kNavigationCsvHeader);
  }
  if (scenario.outputs.mcap_images)
    files_->camera = std::make_unique<CameraFrameLog>(dir / "camera");
  if (scenario.robot.stereo.enabled && scenario.robot.stereo.auto_exposure.enabled) {
    files_->exposure_csv =
        std::make_unique<LogFile>(dir / "camera_exposure.csv", "t,exposure_time_s,gain");
  }
}

RunFolderWriter::~RunFolderWriter() = default;

void RunFolderWriter::WriteCalibration(const scenario::Scenario& scenario,
                                       const RobotBuild& robot) {
  namespace cal = calibration;
  const cal::RobotCalibration& given = robot.given;
  if (given.stereo) {  // the robot has a camera
    WriteFileAtomically(dir_ / cal::kStereoFile,
                        cal::StereoCalibrationJson(*given.stereo, given.stereo_source));
    if (scenario.outputs.save_images == "kitti") {
      // KITTI's images are rectified, with the rectified pair's projections.
      files_->rectifier = std::make_unique<perception::StereoRectifier>(*given.stereo);
      files_->T_left_rect = given.stereo->T_body_left.inverse() * files_->rectifier->T_body_left();
      files_->kitti =
          std::make_unique<perception::KittiWriter>(dir_ / "images", files_->rectifier->camera());
    }
  }
  WriteFileAtomically(dir_ / cal::kImuFile, cal::ImuCalibrationJson(given.imu, given.imu_source));
  WriteFileAtomically(dir_ / cal::kVehicleFile,
                      cal::VehicleCalibrationJson(given.vehicle, given.vehicle_source));
  WriteFileAtomically(dir_ / cal::kGroundTruthFile, cal::GroundTruthCalibrationJson(robot.truth));
}

RunObservers RunFolderWriter::observers() {
  Files& f = *files_;
  RunObservers o;
  // Only with an image export, the bag's images or the auto-exposure's log: a run that
  // looks at no image on the main thread lets the sensor model run on the localization
  // thread (closed_loop.cpp).
  if (f.kitti || f.exposure_csv || f.camera) {
    o.on_stereo = [&f](const StereoFrame& s) {
      if (f.camera) f.camera->Add(s.t_s, *s.left, *s.right);
      if (f.exposure_csv) {
        char line[96];
        std::snprintf(line, sizeof(line), "%.6f,%.9g,%.6g", s.t_s, s.exposure_time_s, s.gain);
        f.exposure_csv->Line(line);
      }
      if (!f.kitti) return;
      // Ground truth of the rectified left camera.
      const Eigen::Isometry3d T_world_cam =
          f.rectifier->identity() ? s.T_world_left : s.T_world_left * f.T_left_rect;
      if (s.index == 0) f.T_world_cam0 = T_world_cam;
      cv::Mat left, right;
      f.rectifier->Rectify(perception::AsCvMat(*s.left), perception::AsCvMat(*s.right), &left,
                           &right);
      f.kitti->Add(s.t_s, left, right, f.T_world_cam0.inverse() * T_world_cam);
    };
  }
  o.on_sample = [&f](const RunSample& s) {
    f.plots.Add(s);
    f.logs.Sample(s);
  };
  o.on_localization_frame = [&f](const LocalizationFrame& l) {
    f.plots.w.Add(l.t_s, l.report.w);
    f.plots.estimates["visual_odometry"].Add(l.t_s, l.visual_odometry);
    f.logs.Frame(l);
  };
  o.on_imu = [&f](const robot::ImuSample& s) { f.logs.Imu(s); };
  o.on_scan = [&f](const robot::RangeScanSample& s) { f.logs.Scan(s); };
  o.on_external_estimate = [&f, dir = dir_](const ExternalEstimate& e) {
    f.plots.estimates[*e.name].Add(e.t_s, e.T_world_body);
    f.logs.External(dir, e);
  };
  if (f.navigation_csv) {
    o.on_navigation_step = [&f](const navigation::NavigationLogEntry& e) {
      f.navigation_csv->Line(NavigationCsvRow(e).c_str());
      f.navigation_log.Add(e);
    };
  }
  return o;
}

std::size_t RunFolderWriter::plot_points() const {
  std::size_t n = 0;
  for (std::size_t k : files_->plots.Sizes()) n += k;
  return n;
}

std::size_t RunFolderWriter::largest_plot_series() const {
  const std::vector<std::size_t> n = files_->plots.Sizes();
  return *std::max_element(n.begin(), n.end());
}

void RunFolderWriter::Close(const scenario::Scenario& scenario, const RunMetrics& metrics) {
  Files& f = *files_;
  if (f.exposure_csv) f.exposure_csv->Close();
  if (f.navigation_csv) {
    f.navigation_csv->Close();
    const navigation::NavigationScene scene = NavigationSceneOf(scenario);
    WriteNavigationMap(
        dir_ / "navigation.png",
        scenario.scene.name + ": " + navigation::ToString(scenario.navigation.method) + " (" +
            metrics.navigation->status + ")",
        f.navigation_log.items(), ObjectCircles(scenario::SceneObjects(scenario)),
        scenario.navigation.safety_radius_m, scene.start, scene.goal, metrics.navigation_subgoals);
  }
  f.logs.Close();
  if (f.kitti) f.kitti->Close();
  if (f.camera) f.camera->Close();
  f.plots.Write(dir_, scenario.scene.name);
  if (scenario.outputs.mcap) WriteRunBag(dir_);
  WriteMetricsJson(metrics, dir_);
}

}  // namespace trackbed::runner
