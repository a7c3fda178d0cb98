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

#include "trackbed/estimation/absolute_orientation.h"
#include "trackbed/estimation/per_distance.h"
#include "trackbed/estimation/stereo_visual_odometry.h"
#include "trackbed/estimation/trajectory.h"
#include "trackbed/estimation/trajectory_metrics.h"
#include "trackbed/perception/kitti_sequence.h"

namespace trackbed::apps {
namespace {

namespace fs = std::filesystem;

struct VoArguments {
  std::string kitti_dir;
  std::string out_dir;
  std::string poses_file;
  bool estimate_disparity_offset = true;
};

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
void PrintFrameToFrameError(const estimation::Trajectory& gt, const estimation::Trajectory& est) {
  const estimation::FrameMotionError e = estimation::FrameToFrameError(gt, est);
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

void RunVo(const VoArguments& args) {
  const perception::KittiSequence sequence(args.kitti_dir, args.poses_file);
  if (sequence.size() == 0) throw std::runtime_error(args.kitti_dir + ": no frames");
  const fs::path out_dir(args.out_dir);
  fs::create_directories(out_dir);

  // KITTI's car: the per-frame and dynamics bounds of a car at up to 100 km/h.
  estimation::StereoVisualOdometryOptions options =
      estimation::StereoVisualOdometryOptions::KittiCar();
  options.estimate_disparity_offset = args.estimate_disparity_offset;
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

  const std::size_t n = trajectory.size();
  std::printf("frames: %zu (%d with motion, %zu failed)\n", n, ok_frames,
              n - 1 - static_cast<std::size_t>(ok_frames));
  if (args.estimate_disparity_offset) {
    std::printf("disparity offset: %.3f px (estimated at the last frame)\n",
                vo.disparity_offset_px());
  }
  std::printf("speed: %.1f frames/s (%.2f ms per frame, Process only)\n",
              process_s > 0.0 ? static_cast<double>(n) / process_s : 0.0,
              1e3 * process_s / static_cast<double>(n));
  if (sequence.has_poses()) {
    estimation::Trajectory gt;
    std::vector<Eigen::Vector3d> p_est, p_gt;
    for (std::size_t k = 0; k < n; ++k) {
      gt.push_back({trajectory[k].t_s, sequence.poses()[k]});
      p_est.push_back(trajectory[k].T_world_body.translation());
      p_gt.push_back(sequence.poses()[k].translation());
    }
    const double length = estimation::PathLength(gt);
    const double end_error = (p_est.back() - p_gt.back()).norm();
    std::printf("end-point error: %.3f m (%s of %.1f m)\n", end_error,
                Figure("%.2f %%", estimation::PercentOfPath(end_error, length)).c_str(), length);
    std::printf("ATE RMSE (SE(3)-aligned positions): %.3f m\n", AteRmseSe3(p_est, p_gt));
    PrintFrameToFrameError(gt, trajectory);
  }
  std::printf("outputs: %s\n", out_dir.string().c_str());
}

}  // namespace

void AddVoCommand(CLI::App& app) {
  auto args = std::make_shared<VoArguments>();
  CLI::App* vo = app.add_subcommand(
      "vo",
      "Stereo visual odometry on a KITTI-layout sequence; writes visual_odometry.tum, "
      "visual_odometry.kitti.txt and vo_frames.csv");
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
  vo->callback([args]() {
    try {
      RunVo(*args);
    } catch (const std::exception& e) {
      std::cerr << "trackbed vo: " << e.what() << "\n";
      throw CLI::RuntimeError(2);
    }
    throw CLI::Success();
  });
}

}  // namespace trackbed::apps
