// `trackbed vo` (see vo_command.h).
#include "vo_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "command_errors.h"
#include "trackbed/common/archive.h"
#include "trackbed/estimation/absolute_orientation.h"
#include "trackbed/estimation/per_distance.h"
#include "trackbed/estimation/stereo_visual_odometry.h"
#include "trackbed/estimation/trajectory.h"
#include "trackbed/estimation/trajectory_metrics.h"
#include "trackbed/perception/kitti_sequence.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::apps {
namespace {

namespace fs = std::filesystem;

struct VoArguments {
  std::string kitti_dir;
  std::string out_dir;
  std::string poses_file;
  bool estimate_disparity_offset = true;
  std::string config_file;        // --config: a YAML map of VO keys
  std::vector<std::string> sets;  // --set KEY=VALUE, in order
};

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The VO's options: KittiCar(), the disparity offset as the flag says, then the keys of
// --config, then each --set in order. The keys are those of a scenario's `estimation.vo`
// section; an unknown key, a wrong type or an invalid value is an error naming it.
estimation::StereoVisualOdometryOptions VoOptions(const VoArguments& args) {
  estimation::StereoVisualOdometryOptions options =
      estimation::StereoVisualOdometryOptions::KittiCar();
  options.estimate_disparity_offset = args.estimate_disparity_offset;
  constexpr archive::Wording kWording = archive::Wording::kDetailed;
  if (!args.config_file.empty()) {
    try {
      archive::Read(archive::ParseYaml(ReadText(args.config_file)), "", kWording, &options);
    } catch (const archive::Error& e) {
      throw std::runtime_error(args.config_file + ": " + (e.path().empty() ? "" : e.path() + ": ") +
                               e.reason());
    }
  }
  for (const std::string& text : args.sets) {
    const scenario::Override o = scenario::ParseOverride(text);
    std::string where;
    try {
      archive::Node root = archive::Write(options);
      archive::Node& target = archive::Reach(root, *archive::ParsePath(o.key), &where);
      target = archive::ParseYaml(o.value, where);
      archive::Read(root, "", kWording, &options);
    } catch (const archive::SyntaxError& e) {
      throw std::runtime_error("--set " + text + ": " + where +
                               ": cannot parse the value as YAML: " + e.detail());
    } catch (const archive::Error& e) {
      throw std::runtime_error("--set " + text + ": " + (e.path().empty() ? where : e.path()) +
                               ": " + e.reason());
    }
  }
  try {
    archive::ValidateAt(options, "");
  } catch (const archive::Error& e) {
    throw std::runtime_error("VO options: " + e.path() + ": " + e.reason());
  }
  return options;
}

std::ofstream OpenForWriting(const fs::path& path) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw std::runtime_error(path.string() + ": cannot be written");
  return out;
}

void Close(std::ofstream& out, const fs::path& path) {
  out.close();
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

/// RMS of the position differences after the rigid alignment (Horn) of the estimate's
/// positions onto the ground truth's.
double AteRmseSe3(const std::vector<Eigen::Vector3d>& est, const std::vector<Eigen::Vector3d>& gt) {
  const estimation::SimilarityTransform S =
      estimation::HornAbsoluteOrientationAnyMinimizer(est, gt, /*with_scale=*/false);
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < est.size(); ++k) sum_sq += (gt[k] - S.Apply(est[k])).squaredNorm();
  return std::sqrt(sum_sq / static_cast<double>(est.size()));
}

// "12.34", or "n/a (< 1 m)" for a per-distance figure that is n/a (NaN: the path is
// under estimation::kMinPathForPerDistanceM).
std::string Figure(const char* format, double value) {
  char buf[64];
  if (std::isfinite(value)) {
    std::snprintf(buf, sizeof(buf), format, value);
  } else {
    std::snprintf(buf, sizeof(buf), "n/a (< %g m)", estimation::kMinPathForPerDistanceM);
  }
  return buf;
}

// The path-length ratio and the frame-to-frame errors (estimation::FrameToFrameError).
void PrintFrameToFrameError(const estimation::FrameMotionError& e, const estimation::Trajectory& gt,
                            const estimation::Trajectory& est) {
  std::printf("path length: %.2f m against %.2f m (ratio %s)\n", estimation::PathLength(est),
              estimation::PathLength(gt), Figure("%.4f", e.path_length_ratio).c_str());
  if (e.trans_pct.count == 0) {
    std::printf("frame to frame: n/a (no frame moved 1 cm)\n");
    return;
  }
  std::printf(
      "frame to frame (%zu frames): translation error median %.3f %%, mean %.3f %% of the "
      "frame's motion; rotation error median %.4f deg, mean %.4f deg; length ratio median "
      "%.4f, mean %.4f\n",
      e.trans_pct.count, e.trans_pct.median, e.trans_pct.mean, e.rot_deg.median, e.rot_deg.mean,
      e.length_ratio.median, e.length_ratio.mean);
}

nlohmann::json StatsJson(const estimation::ErrorStats& s) {
  return {{"median", s.median}, {"mean", s.mean}};
}

// What ran and what it gave, for tools (trackbed transfer): vo_metrics.json.
struct VoFigures {
  std::size_t frames = 0;
  int ok_frames = 0;
  double disparity_offset_px = 0.0;
  nlohmann::json ground_truth;  // null without ground truth
};

void WriteVoMetrics(const fs::path& out_dir, const VoArguments& args,
                    const estimation::StereoVisualOdometryOptions& options, const VoFigures& f) {
  nlohmann::json j;
  j["sequence"] = fs::absolute(args.kitti_dir).lexically_normal().string();
  nlohmann::json settings;
  settings["config"] =
      args.config_file.empty() ? nlohmann::json() : nlohmann::json(args.config_file);
  settings["set"] = args.sets;
  settings["disparity_offset"] = args.estimate_disparity_offset;
  j["settings"] = settings;
  j["options"] = nlohmann::json::parse(archive::ToJson(archive::Write(options)));
  j["frames"] = f.frames;
  j["frames_with_motion"] = f.ok_frames;
  j["disparity_offset_px"] = f.disparity_offset_px;
  j["ground_truth"] = f.ground_truth;
  const fs::path path = out_dir / "vo_metrics.json";
  std::ofstream out = OpenForWriting(path);
  out << j.dump(2) << "\n";
  Close(out, path);
}

// With ground truth: prints the end-point error, the ATE, the path-length ratio and the
// frame-to-frame errors; writes vo_frame_errors.csv; returns the figures as JSON.
nlohmann::json ScoreAgainstGroundTruth(const perception::KittiSequence& sequence,
                                       const estimation::Trajectory& trajectory,
                                       const fs::path& out_dir) {
  const std::size_t n = trajectory.size();
  estimation::Trajectory gt;
  std::vector<Eigen::Vector3d> p_est, p_gt;
  for (std::size_t k = 0; k < n; ++k) {
    gt.push_back({trajectory[k].t_s, sequence.poses()[k]});
    p_est.push_back(trajectory[k].T_world_body.translation());
    p_gt.push_back(sequence.poses()[k].translation());
  }
  const double length = estimation::PathLength(gt);
  const double end_error = (p_est.back() - p_gt.back()).norm();
  const double ate = AteRmseSe3(p_est, p_gt);
  std::printf("end-point error: %.3f m (%s of %.1f m)\n", end_error,
              Figure("%.2f %%", estimation::PercentOfPath(end_error, length)).c_str(), length);
  std::printf("ATE RMSE (SE(3)-aligned positions): %.3f m\n", ate);
  const estimation::FrameMotionError e = estimation::FrameToFrameError(gt, trajectory);
  PrintFrameToFrameError(e, gt, trajectory);

  const fs::path csv_path = out_dir / "vo_frame_errors.csv";
  std::ofstream csv = OpenForWriting(csv_path);
  csv << "frame,t,translation_error_pct,rotation_error_deg,length_ratio\n";
  for (const estimation::FrameMotionSample& s : estimation::FrameToFrameErrors(gt, trajectory)) {
    char line[160];
    std::snprintf(line, sizeof(line), "%zu,%.6f,%.9g,%.9g,%.9g\n", s.frame, trajectory[s.frame].t_s,
                  s.trans_pct, s.rot_deg, s.length_ratio);
    csv << line;
  }
  Close(csv, csv_path);
  return {{"path_length_m", length},
          {"end_point_error_m", end_error},
          {"ate_rmse_m", ate},
          {"path_length_ratio", e.path_length_ratio},
          {"frame_to_frame",
           {{"frames", e.trans_pct.count},
            {"translation_error_pct", StatsJson(e.trans_pct)},
            {"rotation_error_deg", StatsJson(e.rot_deg)},
            {"length_ratio", StatsJson(e.length_ratio)}}}};
}

void WriteTrajectoryFiles(const fs::path& out_dir, const estimation::Trajectory& trajectory) {
  const fs::path tum_path = out_dir / "visual_odometry.tum";
  std::ofstream tum = OpenForWriting(tum_path);
  for (const estimation::StampedPose& pose : trajectory) {
    tum << estimation::FormatTumLine(pose) << "\n";
  }
  Close(tum, tum_path);
  const fs::path kitti_path = out_dir / "visual_odometry.kitti.txt";
  std::ofstream kitti = OpenForWriting(kitti_path);
  for (const estimation::StampedPose& pose : trajectory) {
    kitti << perception::FormatKittiPoseLine(pose.T_world_body) << "\n";
  }
  Close(kitti, kitti_path);
}

void RunVo(const VoArguments& args) {
  // KITTI's car: the per-frame and dynamics bounds of a car at up to 100 km/h; then the
  // user's keys (checked before any image is read).
  const estimation::StereoVisualOdometryOptions options = VoOptions(args);
  const perception::KittiSequence sequence(args.kitti_dir, args.poses_file);
  if (sequence.size() == 0) throw std::runtime_error(args.kitti_dir + ": no frames");
  const fs::path out_dir(args.out_dir);
  fs::create_directories(out_dir);

  estimation::StereoVisualOdometry vo(sequence.calibration(), options);
  estimation::Trajectory trajectory;
  trajectory.reserve(sequence.size());
  const fs::path csv_path = out_dir / "vo_frames.csv";
  std::ofstream csv = OpenForWriting(csv_path);
  csv << "t,status,tracked,inliers,ms,dynamics_constrained,disparity_offset_px\n";
  double process_s = 0.0;
  int ok_frames = 0;
  for (std::size_t k = 0; k < sequence.size(); ++k) {
    const cv::Mat left = sequence.LoadLeft(k);
    const cv::Mat right = sequence.LoadRight(k);
    const double t_s = sequence.times_s()[k];
    const auto start = std::chrono::steady_clock::now();
    const estimation::VoFrameResult r = vo.Process(left, right, t_s);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    process_s += seconds;
    if (r.ok()) ++ok_frames;
    trajectory.push_back({t_s, r.T_world_cam});
    char line[160];
    std::snprintf(line, sizeof(line), "%.6f,%s,%d,%d,%.3f,%d,%.4f\n", t_s,
                  estimation::ToString(r.status), r.tracked, r.inliers, 1e3 * seconds,
                  r.dynamics_constrained ? 1 : 0, r.disparity_offset_px);
    csv << line;
  }
  Close(csv, csv_path);
  WriteTrajectoryFiles(out_dir, trajectory);

  const std::size_t n = trajectory.size();
  std::printf("frames: %zu (%d with motion, %zu failed)\n", n, ok_frames,
              n - 1 - static_cast<std::size_t>(ok_frames));
  if (options.estimate_disparity_offset) {
    std::printf("disparity offset: %.3f px (estimated at the last frame)\n",
                vo.disparity_offset_px());
  }
  std::printf("speed: %.1f frames/s (%.2f ms per frame, Process only)\n",
              process_s > 0.0 ? static_cast<double>(n) / process_s : 0.0,
              1e3 * process_s / static_cast<double>(n));
  VoFigures figures;
  figures.frames = n;
  figures.ok_frames = ok_frames;
  figures.disparity_offset_px = vo.disparity_offset_px();
  if (sequence.has_poses())
    figures.ground_truth = ScoreAgainstGroundTruth(sequence, trajectory, out_dir);
  WriteVoMetrics(out_dir, args, options, figures);
  std::printf("outputs: %s\n", out_dir.string().c_str());
}

}  // namespace

void AddVoCommand(CLI::App& app) {
  auto args = std::make_shared<VoArguments>();
  CLI::App* vo = app.add_subcommand(
      "vo",
      "Stereo visual odometry on a KITTI-layout sequence; writes visual_odometry.tum, "
      "visual_odometry.kitti.txt, vo_frames.csv and vo_metrics.json (with ground truth also "
      "vo_frame_errors.csv)");
  vo->add_option("kitti_dir", args->kitti_dir,
                 "Sequence folder: image_0/, image_1/, calib.txt, times.txt [, poses.txt]")
      ->required()
      ->check(CLI::ExistingDirectory);
  vo->add_option("--out", args->out_dir, "Folder to write")->required();
  vo->add_option("--poses", args->poses_file,
                 "Ground truth in KITTI format (default: kitti_dir/poses.txt if present)")
      ->check(CLI::ExistingFile);
  vo->add_flag("--disparity-offset,!--no-disparity-offset", args->estimate_disparity_offset,
               "Estimate the rig's disparity offset (a rectification's error) frame by frame and "
               "triangulate with it (default); --no-disparity-offset: the disparities as "
               "measured");
  vo->add_option("--config", args->config_file,
                 "A YAML map of VO options, keyed as a scenario's estimation.vo section "
                 "(docs/scenario_format.md), applied over the defaults")
      ->check(CLI::ExistingFile);
  vo->add_option("--set", args->sets,
                 "KEY=VALUE: one VO option by its key under a scenario's estimation.vo "
                 "(tracker.window_px=21, ransac.threshold_px=1), after --config; repeatable");
  vo->callback([args]() { RunCommand("vo", [&] { RunVo(*args); }); });
}

}  // namespace trackbed::apps
