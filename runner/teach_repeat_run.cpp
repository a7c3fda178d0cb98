// The teach & repeat run (see teach_repeat_run.h).
#include "trackbed/runner/teach_repeat_run.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "trackbed/common/median.h"
#include "trackbed/common/random.h"
#include "trackbed/common/units.h"
#include "trackbed/estimation/per_distance.h"
#include "trackbed/estimation/trajectory_io.h"
#include "trackbed/estimation/wheel_odometry.h"
#include "trackbed/perception/lens_undistorter.h"
#include "trackbed/perception/opencv_views.h"
#include "trackbed/plot/plots.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/runner/plot_decimation.h"
#include "trackbed/runner/repeat_commander.h"
#include "trackbed/runner/run_folder.h"
#include "trackbed/teach_repeat/funnel_lane_controller.h"
#include "trackbed/teach_repeat/milestone_builder.h"
#include "trackbed/teach_repeat/milestone_localizer_3d.h"
#include "trackbed/teach_repeat/repeater_factory.h"
#include "trackbed/teach_repeat/running_repeat_score.h"
#include "trackbed/teach_repeat/teach_map.h"
#include "trackbed/teach_repeat/teach_repeat_metrics.h"

namespace trackbed::runner {
namespace fs = std::filesystem;
namespace {

// Bytes of the regular files under `folder`, recursively.
std::uintmax_t FolderBytes(const std::filesystem::path& folder) {
  std::uintmax_t bytes = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file()) bytes += entry.file_size();
  }
  return bytes;
}

// The teach pass: the scenario's own drive, images into the builder with the no-slip
// wheel odometry at each image (metadata; 3D teaching scales milestones by it). Each
// completed milestone's key image goes into `map_dir` at once, so a long route's key
// images are not all held.
teach_repeat::TeachMap Teach(const scenario::Scenario& scenario, const RobotBuild& robot,
                             const fs::path& dir, const fs::path& map_dir,
                             std::vector<Eigen::Vector2d>* taught_path,
                             const RunObservers& observers,
                             std::shared_ptr<sim::TrackMarks> track_marks) {
  scenario::Scenario teach = scenario;
  teach.teach_repeat.enabled = false;
  const scenario::RobotSpec& rs = scenario.robot;
  // The robot software's own view: the left camera and the tracks as calibrated; the
  // milestones are taught on undistorted images (the map has no lens).
  const perception::LensUndistorter undistorter(robot.given.stereo->LeftCamera());
  const geometry::PinholeCamera camera = undistorter.camera();
  teach_repeat::MilestoneBuilder builder(camera, MilestoneBuilderOptionsOf(scenario.teach_repeat));
  estimation::WheelOdometryOptions wo;
  wo.sprocket_radius_m = robot.given.vehicle.sprocket_radius_left_m;
  wo.right_sprocket_radius_m = robot.given.vehicle.sprocket_radius_right_m;
  wo.track_gauge_m = robot.given.vehicle.track_gauge_m;
  wo.icr_expansion = robot.given.vehicle.icr_expansion.value_or(scenario.estimation.icr_expansion);
  wo.ticks_per_rev = rs.encoders.ticks_per_rev;
  wo.estimate_slip = false;
  estimation::WheelOdometry odometry(
      wo, {rs.start.x_m, rs.start.y_m, units::Radians(rs.start.yaw_deg)});
  RunObservers extra;
  extra.on_stereo = [&](const StereoFrame& f) {
    odometry.AddEncoderSample(f.t_s, f.ticks[0], f.ticks[1]);
    cv::Mat image;
    undistorter.Undistort(perception::AsCvMat(*f.left), &image);
    if (builder.AddImage(image, f.t_s, odometry.pose()).milestone_closed) {
      builder.SpillMilestones(map_dir.string());
    }
  };
  extra.on_sample = [&](const RunSample& s) {
    taught_path->push_back(s.chassis.T_world_body.translation().head<2>());
  };
  ClosedLoopOptions loop;
  loop.dir = dir;
  loop.observers = Chained(extra, observers);
  loop.robot = robot;
  loop.track_marks = std::move(track_marks);
  const RunMetrics m = ClosedLoop(teach, std::move(loop)).Run();
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

// The repeater's cumulative loss and recovery counts at one frame.
struct CumulativeRecovery {
  double t_s;
  std::int64_t lost, recovered;
};

// The counts at the last frame at or before `t_s` (zero before the first frame).
CumulativeRecovery CountsAt(const std::vector<CumulativeRecovery>& counts, double t_s) {
  CumulativeRecovery c{t_s, 0, 0};
  for (const CumulativeRecovery& f : counts) {
    if (f.t_s > t_s) break;
    c = f;
  }
  return c;
}

// The window of a crossing place: from the walk's start until recovery_window_s after
// it ends [s].
std::pair<double, double> PlaceWindow(const sim::OccluderSpec& o, double recovery_window_s) {
  double length = 0.0;
  for (std::size_t k = 1; k < o.waypoints.size(); ++k) {
    length += (o.waypoints[k] - o.waypoints[k - 1]).norm();
  }
  return {o.start_s, o.start_s + length / o.speed_mps + recovery_window_s};
}

// The repeat as in the paper's experiment 1: the robot stands still while a person
// crosses (the inner repeater sees every image and keeps tracking, losing and
// recovering features; only its command is held at zero), then drives on.
class StopsForCrossings final : public teach_repeat::Repeater {
 public:
  StopsForCrossings(std::unique_ptr<teach_repeat::Repeater> inner,
                    std::vector<std::pair<double, double>> windows)
      : inner_(std::move(inner)), windows_(std::move(windows)) {}

  teach_repeat::RepeatCommand Update(const cv::Mat& gray, double t_s) override {
    teach_repeat::RepeatCommand c = inner_->Update(gray, t_s);
    for (const auto& [start, end] : windows_) {
      if (t_s >= start && t_s < end) {
        c.twist = {};
        inner_->SetExecutedSpeed(0.0);  // held: no distance driven toward the next frame
      }
    }
    return c;
  }
  void SetExecutedSpeed(double v_mps) override { inner_->SetExecutedSpeed(v_mps); }
  const char* method() const override { return inner_->method(); }
  const teach_repeat::TeachMap& map() const override { return inner_->map(); }

 private:
  std::unique_ptr<teach_repeat::Repeater> inner_;
  std::vector<std::pair<double, double>> windows_;
};

// Choi & Ha's experiment 1, scored: every crossing of teach_repeat.occluders is a place,
// from its start until recovery_window_s after its walk ends; per place, the features
// lost and recovered in that window. recovery_rate is the mean of the per-place rates
// (the paper's 86.18 %), recovery_rate_pooled the pooled one; without crossings both
// are the pooled rate over the whole repeat.
void ScorePlaces(const scenario::TeachRepeatSpec& tr, const std::vector<CumulativeRecovery>& counts,
                 TeachRepeatMetrics* t) {
  std::vector<teach_repeat::RecoveryCounts> places;
  for (const sim::OccluderSpec& o : tr.occluders) {
    TeachRepeatMetrics::Place p;
    std::tie(p.start_s, p.end_s) = PlaceWindow(o, tr.recovery_window_s);
    // Counts of frames strictly before the start belong to earlier places.
    const CumulativeRecovery before =
        CountsAt(counts, std::nextafter(p.start_s, -std::numeric_limits<double>::infinity()));
    const CumulativeRecovery after = CountsAt(counts, p.end_s);
    p.lost = after.lost - before.lost;
    p.recovered = after.recovered - before.recovered;
    places.push_back({p.lost, std::min(p.recovered, p.lost)});
    t->places.push_back(p);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (places.empty()) {
    t->recovery_rate = t->features_lost > 0 ? static_cast<double>(t->features_recovered) /
                                                  static_cast<double>(t->features_lost)
                                            : nan;
    t->recovery_rate_pooled = t->recovery_rate;
    return;
  }
  const teach_repeat::RecoveryMetrics r = teach_repeat::EvaluateRecovery(places);
  for (std::size_t k = 0; k < t->places.size(); ++k) t->places[k].rate = r.per_place_rate[k];
  t->recovery_rate = r.mean_rate;
  t->recovery_rate_pooled = r.pooled_rate;
}

// The repeat pass's scenario: the robot starts near the taught start (the file's
// offset plus a seeded perturbation of up to 5 cm and 2°) and the crossing people are
// there in the repeat only.
scenario::Scenario RepeatScenario(const scenario::Scenario& scenario) {
  const scenario::TeachRepeatSpec& tr = scenario.teach_repeat;
  scenario::Scenario repeat = scenario;
  double dx = tr.start_offset.x_m, dy = tr.start_offset.y_m, dyaw = tr.start_offset.yaw_deg;
  if (tr.start_perturbation) {
    random::Generator rng(scenario.seed ^ 0x7eac4ULL);
    const auto unit = [&rng] { return rng.Uniform(); };
    const double r = 0.05 * std::sqrt(unit()), a = 2.0 * M_PI * unit();
    dx += r * std::cos(a);
    dy += r * std::sin(a);
    dyaw += 2.0 * (2.0 * unit() - 1.0);
  }
  const double yaw0 = units::Radians(scenario.robot.start.yaw_deg);
  repeat.robot.start.x_m += std::cos(yaw0) * dx - std::sin(yaw0) * dy;
  repeat.robot.start.y_m += std::sin(yaw0) * dx + std::cos(yaw0) * dy;
  repeat.robot.start.yaw_deg += dyaw;
  repeat.scene.occluders.insert(repeat.scene.occluders.end(), tr.occluders.begin(),
                                tr.occluders.end());

  return repeat;
}

// teach_repeat_recovery.png: the features recovered per crossing place.
void WriteRecoveryPlot(const scenario::Scenario& scenario, const TeachRepeatMetrics& t,
                       const fs::path& dir) {
  const scenario::TeachRepeatSpec& tr = scenario.teach_repeat;
  std::vector<plot::BarValue> bars;
  for (std::size_t k = 0; k < t.places.size(); ++k) {
    const TeachRepeatMetrics::Place& p = t.places[k];
    char label[64], note[64];
    std::snprintf(label, sizeof(label), "place %zu (%.0f s)", k + 1, p.start_s);
    std::snprintf(note, sizeof(note), "%lld of %lld", static_cast<long long>(p.recovered),
                  static_cast<long long>(p.lost));
    bars.push_back({label, std::isfinite(p.rate) ? 100.0 * p.rate : 0.0, note});
  }
  char title[160];
  std::snprintf(title, sizeof(title), "%s: features recovered per crossing (%s; mean %.1f %%)",
                scenario.scene.name.c_str(), teach_repeat::ToString(tr.method),
                std::isfinite(t.recovery_rate) ? 100.0 * t.recovery_rate : 0.0);
  plot::WriteBarPlot(dir / "teach_repeat_recovery.png", title, "recovered of lost [%]", bars,
                     100.0);
}

// teach_repeat_timing.png: the repeater's time per frame along the route, with its
// median over every 100 frames (flat when the cost does not grow with the route).
// `frames` holds (t [s], time [ms]) and `milestone` (t [s], active milestone) per frame.
void WriteRepeatTimePlot(const scenario::Scenario& scenario, const plot::PlotSeries& frames,
                         const plot::PlotSeries& milestone, const fs::path& dir) {
  plot::PlotSeries medians{"median of 100 frames", {}};
  std::vector<double> block;
  for (std::size_t k = 0; k < frames.points.size(); ++k) {
    block.push_back(frames.points[k].y());
    if (block.size() == 100 || k + 1 == frames.points.size()) {
      medians.points.emplace_back(frames.points[k].x(), Median(block));
      block.clear();
    }
  }
  plot::WriteTimePlot(dir / "teach_repeat_timing.png",
                      scenario.scene.name + ": repeater time per frame (" +
                          teach_repeat::ToString(scenario.teach_repeat.method) + ")",
                      {{"repeater [ms]", {frames, medians}}, {"milestone", {milestone}}});
}

/// The repeater the scenario asks for over `map`, held still through each crossing's
/// window when teach_repeat.stop_for_crossings.
std::unique_ptr<teach_repeat::Repeater> MakeRunRepeater(const scenario::TeachRepeatSpec& tr,
                                                        teach_repeat::TeachMap map) {
  std::unique_ptr<teach_repeat::Repeater> repeater = teach_repeat::MakeRepeater(
      tr.method, std::move(map), FunnelLaneOptionsOf(tr), Localizer3dOptionsOf(tr));
  if (tr.stop_for_crossings && !tr.occluders.empty()) {
    std::vector<std::pair<double, double>> windows;
    for (const sim::OccluderSpec& o : tr.occluders) {
      windows.push_back(PlaceWindow(o, tr.recovery_window_s));
    }
    repeater = std::make_unique<StopsForCrossings>(std::move(repeater), std::move(windows));
  }
  return repeater;
}

}  // namespace

teach_repeat::MilestoneBuilderOptions MilestoneBuilderOptionsOf(
    const scenario::TeachRepeatSpec& tr) {
  teach_repeat::MilestoneBuilderOptions o = tr.milestones;
  o.mode = tr.method;
  return o;
}

teach_repeat::FunnelLaneOptions FunnelLaneOptionsOf(const scenario::TeachRepeatSpec& tr) {
  teach_repeat::FunnelLaneOptions o = tr.funnel_lane;
  o.forward_speed_mps = tr.repeat_speed_mps;
  o.turn_rate_radps = units::Radians(tr.repeat_turn_rate_deg_s);
  return o;
}

teach_repeat::Localizer3dOptions Localizer3dOptionsOf(const scenario::TeachRepeatSpec& tr) {
  teach_repeat::Localizer3dOptions o = tr.localizer_3d;
  o.forward_speed_mps = tr.repeat_speed_mps;
  o.max_yaw_rate_radps = units::Radians(tr.repeat_turn_rate_deg_s);
  return o;
}

namespace {

// A record of the robot's track marks when the scenario asks for one, else null: the
// teach pass fills it and the repeat pass drives over its ruts.
std::shared_ptr<sim::TrackMarks> NewTrackMarks(const scenario::Scenario& scenario) {
  const std::optional<sim::TrackMarkOptions>& o = scenario.scene.appearance.track_marks;
  return o ? std::make_shared<sim::TrackMarks>(*o) : nullptr;
}

}  // namespace

RunMetrics RunTeachRepeat(const scenario::Scenario& scenario, const fs::path& dir,
                          const RunObservers& observers) {
  scenario.Validate();
  fs::create_directories(dir);
  const scenario::TeachRepeatSpec& tr = scenario.teach_repeat;
  std::vector<Eigen::Vector2d> taught;
  teach_repeat::TeachMap map;
  // One robot for both passes (the same as built, calibrated once).
  const RobotBuild robot = BuildRunRobot(scenario);
  const std::shared_ptr<sim::TrackMarks> track_marks = NewTrackMarks(scenario);
  if (tr.map.empty()) {
    map = Teach(scenario, robot, dir / "teach", dir / "teach_map", &taught, observers, track_marks);
    teach_repeat::SaveTeachMap(map, (dir / "teach_map").string());
    // Repeated from the saved map as a map given by teach_repeat.map would be: its key
    // images and features read milestone by milestone.
    map = teach_repeat::LoadTeachMap((dir / "teach_map").string(),
                                     teach_repeat::MapLoading::kOnDemand);
  } else {
    map = teach_repeat::LoadTeachMap(tr.map, teach_repeat::MapLoading::kOnDemand);
    taught = TaughtPathBeside(tr.map);
  }

  const double map_bytes = static_cast<double>(
      FolderBytes(tr.map.empty() ? dir / "teach_map" : std::filesystem::path(tr.map)));
  const scenario::Scenario repeat = RepeatScenario(scenario);

  const int milestones = static_cast<int>(map.milestones.size());
  const int teach_images = static_cast<int>(map.images.size());
  std::unique_ptr<teach_repeat::Repeater> repeater = MakeRunRepeater(tr, std::move(map));

  // The repeat scored as it goes against the taught path; its true path kept for the plot
  // (docs/run_folder.md, "Plots of long runs").
  std::optional<teach_repeat::RunningRepeatScore> score;
  if (!taught.empty()) score.emplace(std::move(taught), tr.path_projection);
  DecimatedPath repeated;
  // teach_repeat.csv: what the repeater saw and did at every frame.
  std::ofstream csv(dir / "teach_repeat.csv", std::ios::out | std::ios::trunc);
  csv << "t,status,v_mps,yaw_rate_radps,milestone,switched,features,tracked,votes_left,"
         "votes_right,votes_straight,mean_error_px,lost,recovered,lateral_offset_m,"
         "heading_error_rad,fallback_2d,progress\n";
  // teach_repeat_timing.csv: the repeater's wall-clock time per frame (machine-dependent,
  // kept apart so that teach_repeat.csv is the same on every machine).
  std::ofstream timing_csv(dir / "teach_repeat_timing.csv", std::ios::out | std::ios::trunc);
  timing_csv << "t,milestone,timing_repeater_ms\n";
  // The time plot's series, per repeat frame.
  plot::PlotSeries frame_ms{"per frame", {}}, milestone{"active milestone", {}};
  RunObservers extra;
  std::vector<CumulativeRecovery> counts;  // per repeat frame
  int switches_by_distance = 0;
  const auto log_step = [&](const RepeatStep& step) {
    const teach_repeat::RepeatCommand& c = step.command;
    counts.push_back({step.t_s, c.features_lost, c.features_recovered});
    switches_by_distance += c.switched_by_distance ? 1 : 0;
    frame_ms.points.emplace_back(step.t_s, 1e3 * step.repeater_s);
    milestone.points.emplace_back(step.t_s, c.milestone);
    char line[512];
    std::snprintf(line, sizeof(line),
                  "%.6f,%s,%.6g,%.6g,%d,%d,%d,%d,%d,%d,%d,%.6g,%d,%d,%.6g,%.6g,%d,%.6g\n", step.t_s,
                  teach_repeat::ToString(c.status), c.twist.v_mps, c.twist.yaw_rate_radps,
                  c.milestone, c.switched ? 1 : 0, c.features, c.tracked, c.votes_left,
                  c.votes_right, c.votes_straight, c.mean_error_px, c.lost, c.recovered,
                  c.lateral_offset_m, c.heading_error_rad, c.fallback_2d ? 1 : 0, c.progress);
    csv << line;
    std::snprintf(line, sizeof(line), "%.6f,%d,%.4f\n", step.t_s, c.milestone,
                  1e3 * step.repeater_s);
    timing_csv << line;
  };
  extra.on_sample = [&](const RunSample& s) {
    if (score) score->Add(s.chassis.T_world_body.translation().head<2>());
    repeated.Add(s.t_s, s.chassis.T_world_body);
  };
  ClosedLoopOptions options;
  options.dir = dir;
  options.observers = Chained(extra, observers);
  options.robot = robot;
  options.track_marks = track_marks;
  options.commander = std::make_unique<RepeatCommander>(
      repeater.get(), repeat.estimation.icr_expansion * repeat.robot.vehicle.track_gauge_m,
      log_step, std::make_shared<perception::LensUndistorter>(robot.given.stereo->LeftCamera()));
  RunMetrics m = ClosedLoop(repeat, std::move(options)).Run();
  csv.close();
  if (!csv) throw std::runtime_error((dir / "teach_repeat.csv").string() + ": cannot write");
  timing_csv.close();
  if (!timing_csv) {
    throw std::runtime_error((dir / "teach_repeat_timing.csv").string() + ": cannot write");
  }
  WriteRepeatTimePlot(scenario, frame_ms, milestone, dir);

  TeachRepeatMetrics t;
  t.method = teach_repeat::ToString(tr.method);
  t.status = m.stop_reason.rfind("repeat ", 0) == 0 ? m.stop_reason.substr(7) : m.stop_reason;
  t.milestones = milestones;
  t.teach_images = teach_images;
  t.switches_by_distance = switches_by_distance;
  t.map_size_mb = map_bytes / 1e6;
  t.features_lost = m.repeat_features_lost;
  t.features_recovered = m.repeat_features_recovered;
  ScorePlaces(tr, counts, &t);
  if (!t.places.empty()) WriteRecoveryPlot(scenario, t, dir);
  if (score && score->samples() > 0) {
    const teach_repeat::RepeatPathMetrics p = score->Metrics(t.status == "finished");
    t.completed = p.completed;
    t.autonomy = p.autonomy;
    t.end_point_error_m = p.end_point_error_m;
    t.lateral_rms_m = p.lateral_rms_m;
    t.lateral_max_m = p.lateral_max_m;
    t.lateral_start_m = p.lateral_start_m;
    t.lateral_end_rms_m = p.lateral_end_rms_m;
    t.taught_length_m = p.taught_length_m;
    t.map_mb_per_100m = estimation::PercentOfPath(t.map_size_mb, p.taught_length_m);  // 100·MB/m
    plot::WriteTrajectoryPlot(dir / "teach_repeat.png",
                              scenario.scene.name + ": teach & repeat (" +
                                  teach_repeat::ToString(tr.method) + ", " + t.status + ")",
                              {{"taught (ground truth)", score->taught()},
                               {"repeated (ground truth)", repeated.Points()}});
  }
  m.teach_repeat = t;
  WriteMetricsJson(m, dir);  // again, now with the score
  return m;
}

}  // namespace trackbed::runner
