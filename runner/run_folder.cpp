// Run folder writer (see run_folder.h).
#include "trackbed/runner/run_folder.h"

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "trackbed/perception/kitti_sequence.h"

#include "trackbed/estimation/pose2.h"
#include "trackbed/estimation/trajectory.h"
#include "trackbed/estimation/trajectory_metrics.h"
#include "trackbed/runner/closed_loop_runner.h"
#include "trackbed/runner/navigation_scenario.h"
#include "trackbed/runner/run_plots.h"
#include "trackbed/runner/teach_repeat_run.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {
namespace {

namespace fs = std::filesystem;

// A text file with a large buffer; checks every write.
class LogFile {
 public:
  LogFile(const fs::path& path, const std::string& header) : path_(path) {
    file_.rdbuf()->pubsetbuf(buffer_, sizeof(buffer_));
    file_.open(path, std::ios::out | std::ios::trunc);
    if (!file_) Fail("cannot create");
    if (!header.empty()) Line(header.c_str());
  }
  void Line(const char* text) {
    file_ << text << '\n';
    if (!file_) Fail("cannot write");
  }
  void Close() {
    file_.close();
    if (!file_) Fail("cannot close");
  }

 private:
  [[noreturn]] void Fail(const char* what) const {
    throw std::runtime_error(path_.string() + ": " + what + ": " + std::strerror(errno));
  }
  fs::path path_;
  char buffer_[1 << 16];
  std::ofstream file_;
};

void WriteAtomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::out | std::ios::trunc);
    f << text;
    f.close();
    if (!f) throw std::runtime_error(tmp.string() + ": cannot write: " + std::strerror(errno));
  }
  fs::rename(tmp, path);
}

nlohmann::ordered_json SlipJson(const SlipStats& s) {
  nlohmann::ordered_json j;
  j["mean_abs_slip_ratio"] = s.mean_abs_ratio();
  j["mean_slip_ratio"] = s.mean_ratio();
  j["mean_abs_slip_velocity_mps"] = s.mean_abs_velocity_mps();
  j["samples"] = s.samples;
  return j;
}

// Intrinsics and extrinsics of the stereo rig, as used for rendering.
std::string StereoCalibrationJson(const robot::StereoRig& rig) {
  const sim::PinholeIntrinsics& K = rig.intrinsics();
  auto pose = [](const Eigen::Isometry3d& T) {
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (int r = 0; r < 4; ++r) {
      rows.push_back({T.matrix()(r, 0), T.matrix()(r, 1), T.matrix()(r, 2), T.matrix()(r, 3)});
    }
    return rows;
  };
  nlohmann::ordered_json j;
  j["width_px"] = K.width_px;
  j["height_px"] = K.height_px;
  j["fx"] = K.fx;
  j["fy"] = K.fy;
  j["cx"] = K.cx;
  j["cy"] = K.cy;
  j["baseline_m"] = rig.options().baseline_m;
  j["T_body_left"] = pose(rig.T_body_left());
  j["T_body_right"] = pose(rig.T_body_right());
  j["convention"] =
      "OpenCV camera axes (x right, y down, z forward); pixel (0,0) is the centre of the top-left "
      "pixel; T_body_cam maps camera coordinates to body coordinates";
  return j.dump(2) + "\n";
}

// What the plots need, gathered at 10 Hz while the run goes.
struct PlotData {
  estimation::Trajectory truth;
  std::map<std::string, estimation::Trajectory> estimates;  // name → poses
  std::vector<Eigen::Vector2d> w, slip_left_true, slip_left_est, slip_right_true, slip_right_est;

  void Add(const RunSample& s) {
    if (std::lround(s.t_s * 100.0) % 10 != 0) return;  // every 0.1 s
    truth.push_back({s.t_s, s.chassis.T_world_body});
    if (!s.estimate) return;
    const EstimateSample& e = *s.estimate;
    estimates["wheel_odometry"].push_back({s.t_s, e.wheel_odometry});
    estimates["wheel_odometry_noslip"].push_back({s.t_s, e.wheel_odometry_noslip});
    estimates["ekf"].push_back({s.t_s, e.ekf});
    if (e.has_camera) estimates["fused"].push_back({s.t_s, e.fused});
    slip_left_true.emplace_back(s.t_s, s.tracks[0].slip_velocity_mps);
    slip_right_true.emplace_back(s.t_s, s.tracks[1].slip_velocity_mps);
    slip_left_est.emplace_back(s.t_s, e.slip.left_mps);
    slip_right_est.emplace_back(s.t_s, e.slip.right_mps);
  }

  // trajectories.png, error_histogram.png and (with a camera) fusion.png.
  void Write(const fs::path& dir, const std::string& scene) const {
    if (truth.size() < 2 || estimates.empty()) return;
    auto xy = [](const estimation::Trajectory& t) {
      std::vector<Eigen::Vector2d> pts;
      for (const estimation::StampedPose& p : t)
        pts.push_back(p.T_world_body.translation().head<2>());
      return pts;
    };
    std::vector<PlotSeries> paths{{"ground truth", xy(truth)}};
    for (const auto& [name, t] : estimates) paths.push_back({name, xy(t)});
    WriteTrajectoryPlot(dir / "trajectories.png", scene + ": trajectories over the true path",
                        paths);
    std::vector<double> edges;
    for (int k = 0; k <= 20; ++k) edges.push_back(0.05 * k);
    std::vector<HistogramSeries> bars;
    for (const auto& [name, t] : estimates) {
      const estimation::DistanceHistogram h = estimation::DistanceErrorHistogram(t, truth, edges);
      HistogramSeries b{name + " (>1 m: " + std::to_string(h.above) + ")", {}};
      for (std::size_t c : h.counts) b.counts.push_back(static_cast<double>(c) / h.total());
      bars.push_back(b);
    }
    WriteHistogramPlot(dir / "error_histogram.png",
                       scene + ": distance of each estimate to the true path",
                       "distance to the true path [m]", edges, bars, /*first_color=*/1);
    if (w.empty()) return;
    WriteTimePlot(
        dir / "fusion.png", scene + ": fusion weight and track slip",
        {{"w (wheel odometry)", {{"w", w}}},
         {"left slip [m/s]", {{"true", slip_left_true}, {"estimated", slip_left_est}}},
         {"right slip [m/s]", {{"true", slip_right_true}, {"estimated", slip_right_est}}}});
  }
};

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
      m.distance_m > 0 ? 100.0 * (m.encoder_distance_m - m.distance_m) / m.distance_m : 0.0;
  j["min_com_height_m"] = m.min_com_height_m;
  nlohmann::ordered_json slip;
  slip["left"] = SlipJson(m.slip[robot::kLeft]);
  slip["right"] = SlipJson(m.slip[robot::kRight]);
  nlohmann::ordered_json by_material = nlohmann::ordered_json::object();
  for (const auto& [name, stats] : m.slip_by_material) by_material[name] = SlipJson(stats);
  slip["by_material"] = by_material;
  j["slip"] = slip;
  j["icr_expansion"] = {{"chi", m.icr.chi},
                        {"samples", m.icr.samples_used},
                        {"rms_residual_radps", m.icr.rms_residual_radps}};
  j["stereo_frames"] = m.stereo_frames;
  nlohmann::ordered_json estimators = nlohmann::ordered_json::object();
  for (const auto& [name, e] : m.estimators) {
    estimators[name] = {
        {"ate_rmse_m", e.ate_rmse_m},       {"ate3d_se3_rmse_m", e.ate3d_se3_rmse_m},
        {"final_error_m", e.final_error_m}, {"final_error_pct", e.final_error_pct},
        {"rpe_trans_pct", e.rpe_trans_pct}, {"samples", e.samples}};
  }
  j["estimators"] = estimators;
  const LocalizationSummary& loc = m.localization;
  j["localization"] = {{"vo_frames", loc.vo_frames},
                       {"camera_blackout_frames", loc.camera_blackout_frames},
                       {"vo_failures", loc.vo_failures},
                       {"vo_dynamics_constrained", loc.vo_dynamics_constrained},
                       {"vo_coasted", loc.vo_coasted},
                       {"mean_inliers", loc.mean_inliers},
                       {"mean_fusion_w", loc.mean_fusion_w},
                       {"slip_estimate_rmse_mps", loc.slip_estimate_rmse_mps}};
  j["timing"] = {{"render_s", m.render_wall_s},
                 {"sensor_model_s", m.sensor_model_wall_s},
                 {"estimation_s", m.estimation_wall_s},
                 {"physics_s", m.physics_wall_s},
                 {"control_s", m.control_wall_s},
                 {"sensing_s", m.sensing_wall_s},
                 {"io_s", m.io_wall_s}};
  j["memory"] = {{"peak_rss_mb", m.peak_rss_mb}};
  if (m.teach_repeat) {
    const TeachRepeatMetrics& t = *m.teach_repeat;
    const auto finite_or_null = [](double v) {
      return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json();
    };
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
                         {"recovery_rate", finite_or_null(t.recovery_rate)},
                         {"recovery_rate_pooled", finite_or_null(t.recovery_rate_pooled)},
                         {"milestones", t.milestones},
                         {"teach_images", t.teach_images}};
    nlohmann::ordered_json places = nlohmann::ordered_json::array();
    for (const TeachRepeatMetrics::Place& p : t.places) {
      places.push_back({{"start_s", p.start_s},
                        {"end_s", p.end_s},
                        {"lost", p.lost},
                        {"recovered", p.recovered},
                        {"rate", finite_or_null(p.rate)}});
    }
    j["teach_repeat"]["places"] = places;
  }
  if (m.navigation) {
    const navigation::NavigationMetrics& n = *m.navigation;
    const auto finite_or_null = [](double v) {
      return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json();
    };
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
        {"min_clearance_m", finite_or_null(n.min_clearance_m)},
        {"mean_clearance_m", finite_or_null(n.mean_clearance_m)},
        {"collisions", n.collisions},
        {"integrated_abs_jerk", n.integrated_abs_jerk},
        {"subgoals", n.subgoals}};
  }
  return j.dump(2) + "\n";
}

namespace {

// Observers that call `a`'s and then `b`'s.
RunObservers Chained(const RunObservers& a, const RunObservers& b) {
  return CombineObservers(a, b, [](const auto& f, const auto& g) -> std::decay_t<decltype(f)> {
    if (!f) return g;
    if (!g) return f;
    return [f, g](const auto& x) {
      f(x);
      g(x);
    };
  });
}

constexpr char kNavigationCsvHeader[] =
    "t,x_m,y_m,yaw_rad,v_mps,yaw_rate_radps,left_radps,right_radps,target_x_m,target_y_m,"
    "subgoal_active,clearance_m";

std::string NavigationCsvRow(const navigation::NavigationLogEntry& e) {
  char line[512];
  std::snprintf(line, sizeof(line), "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%.9g",
                e.t_s, e.x_m, e.y_m, e.yaw_rad, e.v_mps, e.yaw_rate_radps, e.left_radps,
                e.right_radps, e.target_x_m, e.target_y_m, e.subgoal_active ? 1 : 0, e.clearance_m);
  return line;
}

// The path among the obstacles, their safety circles and the sub-goals (Jung & Kim
// 2014, figs. 5–8).
void WriteNavigationMap(const fs::path& png, const std::string& title,
                        const std::vector<navigation::NavigationLogEntry>& log,
                        const std::vector<navigation::Circle>& obstacles, double safety_radius_m,
                        const estimation::Pose2& start, const estimation::Pose2& goal,
                        const std::vector<navigation::SubgoalRecord>& subgoals) {
  std::vector<PlotCircle> circles;
  for (const navigation::Circle& c : obstacles) {
    circles.push_back({c.centre, c.radius_m + safety_radius_m, false});
  }
  for (const navigation::Circle& c : obstacles) circles.push_back({c.centre, c.radius_m});
  std::vector<PlotMarker> markers = {{{start.x, start.y}, "start"}, {{goal.x, goal.y}, "goal"}};
  for (std::size_t k = 0; k < subgoals.size(); ++k) {
    markers.push_back({subgoals[k].position, "sub-goal " + std::to_string(k + 1)});
  }
  PlotSeries path{"path (ground truth)", {}};
  for (const navigation::NavigationLogEntry& e : log) path.points.emplace_back(e.x_m, e.y_m);
  WriteMapPlot(png, title, {path}, circles, markers);
}

// The scene's colliding objects as circles, for the map: cylinders as they are, boxes
// as chains of circles along their longer side.
std::vector<navigation::Circle> ObjectCircles(const std::vector<sim::StaticObject>& objects) {
  std::vector<navigation::Circle> circles;
  for (const sim::StaticObject& o : objects) {
    if (!o.collides) continue;
    if (o.shape == sim::StaticObject::Shape::kCylinder) {
      circles.push_back({o.center_m, o.radius_m});
      continue;
    }
    const bool along_x = o.size_m.x() >= o.size_m.y();
    const double half_long = 0.5 * (along_x ? o.size_m.x() : o.size_m.y());
    const double radius = 0.5 * (along_x ? o.size_m.y() : o.size_m.x());
    const double axis_yaw = o.yaw_rad + (along_x ? 0.0 : M_PI / 2);
    const Eigen::Vector2d u(std::cos(axis_yaw), std::sin(axis_yaw));
    const double reach = std::max(half_long - radius, 0.0);
    const std::vector<navigation::Circle> chain = navigation::WallCircles(
        o.center_m - reach * u, o.center_m + reach * u, radius, std::max(radius, 0.05));
    circles.insert(circles.end(), chain.begin(), chain.end());
  }
  return circles;
}

// `navigation.mode: kinematic`: the paper's differential-drive simulation, no physics
// and no camera. Writes ground_truth.tum (the simulated pose), navigation.csv, the map
// plot and metrics.json.
RunMetrics RunKinematicNavigation(const scenario::Scenario& scenario, const fs::path& dir) {
  const auto wall_start = std::chrono::steady_clock::now();
  const navigation::NavigationScene scene = NavigationSceneOf(scenario);
  const std::unique_ptr<navigation::Navigator> navigator = navigation::MakeNavigator(
      scenario.navigation.method, NavigatorOptionsOf(scenario), scene.goal);
  const navigation::KinematicRun run =
      navigation::RunKinematicSimulation(scene, *navigator, KinematicOptionsOf(scenario));

  LogFile truth(dir / "ground_truth.tum", "");
  LogFile csv(dir / "navigation.csv", kNavigationCsvHeader);
  RunMetrics m;
  for (std::size_t k = 0; k < run.log.size(); ++k) {
    const navigation::NavigationLogEntry& e = run.log[k];
    truth.Line(
        estimation::FormatTumLine({e.t_s, estimation::ToIsometry({e.x_m, e.y_m, e.yaw_rad}, 0.0)})
            .c_str());
    csv.Line(NavigationCsvRow(e).c_str());
    if (k > 0) {
      // The commanded wheel travel of the step: what encoders on this robot would count.
      m.encoder_distance_m += std::abs(run.log[k - 1].v_mps) * (e.t_s - run.log[k - 1].t_s);
    }
  }
  truth.Close();
  csv.Close();

  WriteNavigationMap(
      dir / "navigation.png",
      scenario.scene.name + ": " + scenario.navigation.method + " (" + run.metrics.status + ")",
      run.log, scene.obstacles, scenario.navigation.safety_radius_m, scene.start, scene.goal,
      run.subgoals);

  m.completed = true;
  m.stop_reason = "navigation " + run.metrics.status;
  m.sim_time_s = run.metrics.duration_s;
  m.distance_m = run.metrics.path_length_m;
  m.navigation_method = scenario.navigation.method;
  m.navigation = run.metrics;
  m.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return m;
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
               "t,v_x_mps,v_y_mps,v_z_mps,omega_x_radps,omega_y_radps,omega_z_radps") {
    if (!scenario.estimation.enabled) return;
    wheel_tum_ = std::make_unique<LogFile>(dir / "wheel_odometry.tum", "");
    noslip_tum_ = std::make_unique<LogFile>(dir / "wheel_odometry_noslip.tum", "");
    ekf_tum_ = std::make_unique<LogFile>(dir / "ekf.tum", "");
    if (!scenario.robot.stereo.enabled) return;
    fused_tum_ = std::make_unique<LogFile>(dir / "fused.tum", "");
    vo_tum_ = std::make_unique<LogFile>(dir / "visual_odometry.tum", "");
    fusion_csv_ = std::make_unique<LogFile>(
        dir / "fusion.csv",
        "t,slip_velocity_mps,features,w,vo_status,vo_tracked,camera_blackout,w_rule,"
        "vo_dynamics_constrained");
  }

  void Sample(const RunSample& s);
  void Frame(const LocalizationFrame& f);
  void Imu(const robot::ImuSample& s);
  void Close() {
    for (LogFile* f : {&truth_, &twist_, &encoders_, &slip_, &tracks_, &imu_}) f->Close();
    for (auto* f : {&wheel_tum_, &noslip_tum_, &ekf_tum_, &fused_tum_, &vo_tum_, &fusion_csv_}) {
      if (*f) (*f)->Close();
    }
  }

 private:
  LogFile truth_, encoders_, slip_, tracks_, imu_, twist_;
  std::unique_ptr<LogFile> wheel_tum_, noslip_tum_, ekf_tum_, fused_tum_, vo_tum_, fusion_csv_;
  char line_[512];
};

void RunLogs::Sample(const RunSample& s) {
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
}

void RunLogs::Imu(const robot::ImuSample& s) {
  std::snprintf(line_, sizeof(line_), "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", s.t_s, s.gyro_radps.x(),
                s.gyro_radps.y(), s.gyro_radps.z(), s.accel_mps2.x(), s.accel_mps2.y(),
                s.accel_mps2.z());
  imu_.Line(line_);
}

}  // namespace

void WriteMetricsJson(const RunMetrics& metrics, const fs::path& dir) {
  WriteAtomically(dir / "metrics.json", MetricsJson(metrics));
}

RunMetrics RunToFolder(const scenario::Scenario& scenario, const fs::path& dir) {
  if (scenario.teach_repeat.enabled) return RunTeachRepeat(scenario, dir);
  return RunToFolderWith(scenario, dir, {}, nullptr);
}

RunMetrics RunToFolderWith(const scenario::Scenario& scenario, const fs::path& dir,
                           const RunObservers& extra, teach_repeat::Repeater* repeater) {
  scenario.Validate();
  fs::create_directories(dir);
  fs::remove(dir / "metrics.json");  // no stale result may pass for this run's
  WriteAtomically(dir / "scenario.yaml",
                  scenario::ScenarioToYaml(scenario::WithBuiltinMaterialsResolved(scenario)));

  RunMetrics metrics;
  try {
    if (scenario.navigation.enabled &&
        scenario.navigation.mode == scenario::NavigationSpec::Mode::kKinematic) {
      metrics = RunKinematicNavigation(scenario, dir);
      WriteMetricsJson(metrics, dir);
      return metrics;
    }
    RunLogs logs(dir, scenario);
    RunObservers observers;
    PlotData plots;
    std::unique_ptr<perception::KittiWriter> kitti;
    Eigen::Isometry3d T_world_cam0 = Eigen::Isometry3d::Identity();
    if (scenario.robot.stereo.enabled) {
      const robot::StereoRig rig(scenario.robot.stereo);
      WriteAtomically(dir / "stereo_calibration.json", StereoCalibrationJson(rig));
      if (scenario.outputs.save_images == "kitti") {
        const sim::PinholeIntrinsics& K = rig.intrinsics();
        kitti = std::make_unique<perception::KittiWriter>(
            dir / "images", perception::StereoCalibration::FromIntrinsics(
                                K.fx, K.fy, K.cx, K.cy, scenario.robot.stereo.baseline_m));
      }
    }
    // Only with an image export: a run that looks at no image on the main thread lets
    // the sensor model run on the localization thread (closed_loop_runner.cpp).
    if (kitti) {
      observers.on_stereo = [&](const StereoFrame& f) {
        if (f.index == 0) T_world_cam0 = f.T_world_left;
        auto as_mat = [](const sim::GrayImage& g) {
          return cv::Mat(g.height, g.width, CV_8UC1, const_cast<std::uint8_t*>(g.pixels.data()));
        };
        kitti->Add(f.t_s, as_mat(*f.left), as_mat(*f.right),
                   T_world_cam0.inverse() * f.T_world_left);
      };
    }
    observers.on_sample = [&](const RunSample& s) {
      plots.Add(s);
      logs.Sample(s);
    };
    observers.on_localization_frame = [&](const LocalizationFrame& f) {
      plots.w.emplace_back(f.t_s, f.report.w);
      plots.estimates["visual_odometry"].push_back({f.t_s, f.visual_odometry});
      logs.Frame(f);
    };
    observers.on_imu = [&](const robot::ImuSample& s) { logs.Imu(s); };
    std::unique_ptr<LogFile> navigation_csv;
    std::vector<navigation::NavigationLogEntry> navigation_log;
    if (scenario.navigation.enabled) {
      navigation_csv = std::make_unique<LogFile>(dir / "navigation.csv", kNavigationCsvHeader);
      observers.on_navigation_step = [&](const navigation::NavigationLogEntry& e) {
        navigation_csv->Line(NavigationCsvRow(e).c_str());
        navigation_log.push_back(e);
      };
    }
    metrics = RunClosedLoop(scenario, Chained(observers, extra), repeater);
    if (navigation_csv) {
      navigation_csv->Close();
      const navigation::NavigationScene scene = NavigationSceneOf(scenario);
      WriteNavigationMap(dir / "navigation.png",
                         scenario.scene.name + ": " + scenario.navigation.method + " (" +
                             metrics.navigation->status + ")",
                         navigation_log, ObjectCircles(scenario.scene.objects),
                         scenario.navigation.safety_radius_m, scene.start, scene.goal,
                         metrics.navigation_subgoals);
    }
    logs.Close();
    if (kitti) kitti->Close();
    plots.Write(dir, scenario.scene.name);
  } catch (const std::exception& e) {
    metrics.completed = false;
    metrics.stop_reason = std::string("failed: ") + e.what();
    WriteMetricsJson(metrics, dir);
    throw;
  }
  WriteMetricsJson(metrics, dir);
  return metrics;
}

}  // namespace trackbed::runner
