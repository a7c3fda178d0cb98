// The teach & repeat run (see teach_repeat_run.h).
#include "trackbed/scenes/teach_repeat_run.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

#include "trackbed/estimation/trajectory_io.h"
#include "trackbed/estimation/wheel_odometry.h"
#include "trackbed/navigation/funnel_lane_controller.h"
#include "trackbed/navigation/milestone_builder.h"
#include "trackbed/navigation/milestone_localizer_3d.h"
#include "trackbed/navigation/teach_map.h"
#include "trackbed/navigation/teach_repeat_metrics.h"
#include "trackbed/perception/kitti_sequence.h"
#include "trackbed/scenes/run_folder.h"
#include "trackbed/scenes/run_plots.h"

namespace trackbed::scenes {
namespace fs = std::filesystem;
namespace {

double Radians(double deg) { return deg * M_PI / 180.0; }

// The teach pass: the scenario's own drive, images into the builder with the no-slip
// wheel odometry at each image (metadata; 3D teaching scales milestones by it).
navigation::TeachMap Teach(const Scenario& scenario, const fs::path& dir,
                           std::vector<Eigen::Vector2d>* taught_path) {
  Scenario teach = scenario;
  teach.teach_repeat.enabled = false;
  const RobotSpec& rs = scenario.robot;
  const robot::StereoRig rig(rs.stereo);
  const sim::PinholeIntrinsics& K = rig.intrinsics();
  const navigation::CameraIntrinsics camera = navigation::CameraIntrinsics::FromCalibration(
      perception::StereoCalibration::FromIntrinsics(K.fx, K.fy, K.cx, K.cy, rs.stereo.baseline_m),
      cv::Size(rs.stereo.width_px, rs.stereo.height_px));
  navigation::MilestoneBuilderOptions options;
  options.mode = scenario.teach_repeat.method == "3d" ? navigation::TeachMode::k3d
                                                      : navigation::TeachMode::k2d;
  navigation::MilestoneBuilder builder(camera, options);
  estimation::WheelOdometryOptions wo;
  wo.sprocket_radius_m = rs.vehicle.sprocket_radius_m;
  wo.track_gauge_m = rs.vehicle.track_gauge_m;
  wo.icr_expansion = scenario.estimation.icr_expansion;
  wo.ticks_per_rev = rs.encoders.ticks_per_rev;
  wo.estimate_slip = false;
  estimation::WheelOdometry odometry(wo, {rs.start.x_m, rs.start.y_m, Radians(rs.start.yaw_deg)});
  RunObservers extra;
  extra.on_stereo = [&](const StereoFrame& f) {
    odometry.AddEncoderSample(f.t_s, f.ticks[0], f.ticks[1]);
    const cv::Mat left(f.left->height, f.left->width, CV_8UC1,
                       const_cast<std::uint8_t*>(f.left->pixels.data()));
    builder.AddImage(left, f.t_s, odometry.pose());
  };
  extra.on_sample = [&](const RunSample& s) {
    taught_path->push_back(s.chassis.T_world_body.translation().head<2>());
  };
  const RunMetrics m = RunToFolderWith(teach, dir, extra, nullptr);
  if (!m.completed) throw std::runtime_error("teach pass stopped: " + m.stop_reason);
  return builder.Finish();
}

// The taught ground truth of a map saved by an earlier run: its teach/ folder.
std::vector<Eigen::Vector2d> TaughtPathBeside(const fs::path& map_dir) {
  std::vector<Eigen::Vector2d> path;
  const fs::path truth = map_dir.parent_path() / "teach" / "ground_truth.tum";
  if (!fs::exists(truth)) return path;
  for (const estimation::StampedPose& p : estimation::ReadTrajectory(truth).poses) {
    path.push_back(p.T_world_body.translation().head<2>());
  }
  return path;
}

}  // namespace

RunMetrics RunTeachRepeat(const Scenario& scenario, const fs::path& dir) {
  scenario.Validate();
  fs::create_directories(dir);
  const TeachRepeatSpec& tr = scenario.teach_repeat;
  std::vector<Eigen::Vector2d> taught;
  navigation::TeachMap map;
  if (tr.map.empty()) {
    map = Teach(scenario, dir / "teach", &taught);
    navigation::SaveTeachMap(map, (dir / "teach_map").string());
  } else {
    map = navigation::LoadTeachMap(tr.map);
    taught = TaughtPathBeside(tr.map);
  }

  // The repeat starts near the taught start: the file's offset plus a seeded
  // perturbation of up to 5 cm and 2°.
  Scenario repeat = scenario;
  double dx = tr.start_offset.x_m, dy = tr.start_offset.y_m, dyaw = tr.start_offset.yaw_deg;
  if (tr.start_perturbation) {
    std::mt19937_64 rng(scenario.seed ^ 0x7eac4ULL);
    const auto unit = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
    const double r = 0.05 * std::sqrt(unit()), a = 2.0 * M_PI * unit();
    dx += r * std::cos(a);
    dy += r * std::sin(a);
    dyaw += 2.0 * (2.0 * unit() - 1.0);
  }
  const double yaw0 = Radians(scenario.robot.start.yaw_deg);
  repeat.robot.start.x_m += std::cos(yaw0) * dx - std::sin(yaw0) * dy;
  repeat.robot.start.y_m += std::sin(yaw0) * dx + std::cos(yaw0) * dy;
  repeat.robot.start.yaw_deg += dyaw;

  navigation::FunnelLaneOptions o2;
  o2.forward_speed_mps = tr.repeat_speed_mps;
  o2.turn_rate_radps = Radians(tr.repeat_turn_rate_deg_s);
  navigation::Localizer3dOptions o3;
  o3.forward_speed_mps = tr.repeat_speed_mps;
  o3.max_yaw_rate_radps = Radians(tr.repeat_turn_rate_deg_s);
  const int milestones = static_cast<int>(map.milestones.size());
  const int teach_images = static_cast<int>(map.images.size());
  const std::unique_ptr<navigation::Repeater> repeater =
      navigation::MakeRepeater(tr.method, std::move(map), o2, o3);

  std::vector<Eigen::Vector2d> repeated;
  // teach_repeat.csv: what the repeater saw and did at every frame.
  std::ofstream csv(dir / "teach_repeat.csv", std::ios::out | std::ios::trunc);
  csv << "t,status,v_mps,yaw_rate_radps,milestone,switched,features,tracked,votes_left,"
         "votes_right,votes_straight,mean_error_px,lost,recovered,lateral_offset_m,"
         "heading_error_rad,fallback_2d,progress\n";
  RunObservers extra;
  extra.on_repeat_step = [&](const std::pair<double, navigation::RepeatCommand>& step) {
    const navigation::RepeatCommand& c = step.second;
    char line[512];
    std::snprintf(line, sizeof(line),
                  "%.6f,%s,%.6g,%.6g,%d,%d,%d,%d,%d,%d,%d,%.6g,%d,%d,%.6g,%.6g,%d,%.6g\n",
                  step.first, navigation::ToString(c.status), c.twist.v_mps, c.twist.yaw_rate_radps,
                  c.milestone, c.switched ? 1 : 0, c.features, c.tracked, c.votes_left,
                  c.votes_right, c.votes_straight, c.mean_error_px, c.lost, c.recovered,
                  c.lateral_offset_m, c.heading_error_rad, c.fallback_2d ? 1 : 0, c.progress);
    csv << line;
  };
  extra.on_sample = [&](const RunSample& s) {
    repeated.push_back(s.chassis.T_world_body.translation().head<2>());
  };
  RunMetrics m = RunToFolderWith(repeat, dir, extra, repeater.get());
  csv.close();
  if (!csv) throw std::runtime_error((dir / "teach_repeat.csv").string() + ": cannot write");

  TeachRepeatMetrics t;
  t.method = tr.method;
  t.status = m.stop_reason.rfind("repeat ", 0) == 0 ? m.stop_reason.substr(7) : m.stop_reason;
  t.milestones = milestones;
  t.teach_images = teach_images;
  t.features_lost = m.repeat_features_lost;
  t.features_recovered = m.repeat_features_recovered;
  t.recovery_rate = t.features_lost > 0 ? static_cast<double>(t.features_recovered) /
                                              static_cast<double>(t.features_lost)
                                        : std::numeric_limits<double>::quiet_NaN();
  if (!taught.empty() && !repeated.empty()) {
    const navigation::RepeatPathMetrics p =
        navigation::EvaluateRepeatPath(taught, repeated, t.status == "finished");
    t.completed = p.completed;
    t.autonomy = p.autonomy;
    t.end_point_error_m = p.end_point_error_m;
    t.lateral_rms_m = p.lateral_rms_m;
    t.lateral_max_m = p.lateral_max_m;
    t.taught_length_m = p.taught_length_m;
    WriteTrajectoryPlot(
        dir / "teach_repeat.png",
        scenario.scene.name + ": teach & repeat (" + tr.method + ", " + t.status + ")",
        {{"taught (ground truth)", taught}, {"repeated (ground truth)", repeated}});
  }
  m.teach_repeat = t;
  WriteMetricsJson(m, dir);  // again, now with the score
  return m;
}

}  // namespace trackbed::scenes
