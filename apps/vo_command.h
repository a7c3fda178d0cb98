// `trackbed vo KITTI_DIR --out DIR [--poses FILE] [--config FILE] [--set KEY=VALUE ...]`:
// stereo visual odometry on a real sequence in KITTI layout.
//
// The VO's options: StereoVisualOdometryOptions::KittiCar() with the rig's disparity
// offset estimated (--no-disparity-offset: not), then the keys of --config (a YAML map)
// and each --set in order, keyed as a scenario's `estimation.vo` section
// (docs/scenario_format.md); an unknown key or a bad value stops the command naming it.
//
// Writes, in DIR (created if needed):
//   visual_odometry.tum        `t x y z qx qy qz qw`, t from times.txt: the left camera's
//                              pose in the first left camera's frame;
//   visual_odometry.kitti.txt  the same poses as KITTI 3×4 lines (one per frame);
//   vo_frames.csv              `t,status,tracked,inliers,ms,dynamics_constrained` per
//                              frame (ms: wall time of StereoVisualOdometry::Process);
//   vo_metrics.json            the sequence, the settings given and the options as
//                              resolved, frame counts, and with ground truth the figures
//                              printed (docs/transfer.md);
//   vo_frame_errors.csv        with ground truth: `frame,t,translation_error_pct,
//                              rotation_error_deg,length_ratio` for each pair of
//                              consecutive frames (estimation::FrameToFrameErrors).
// Prints the number of frames, frames per second (wall clock of Process only, images
// are read outside it), and, when ground truth exists (poses.txt in the folder or
// --poses), the end-point error [m, % of the ground-truth path length] and the ATE RMSE
// after SE(3) alignment of the positions (Horn).
#pragma once

#include <CLI/CLI.hpp>

namespace trackbed::apps {

/// Registers the `vo` subcommand on `app`. The command runs in the subcommand's
/// callback, i.e. inside app.parse(), and ends parsing by throwing: CLI::Success on
/// success (exit status 0) or, after printing a one-line reason to stderr,
/// CLI::RuntimeError(2) — so `catch (const CLI::ParseError& e) { return app.exit(e); }`
/// around parse() gives the right exit status.
void AddVoCommand(CLI::App& app);

}  // namespace trackbed::apps
