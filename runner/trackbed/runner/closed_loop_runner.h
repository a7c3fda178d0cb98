// The closed loop: the simulated world and robot on one clock, the drive
// (script or pure-pursuit driver) commanding the tracks, sensors sampled at
// their rates, and ground truth scored as the run goes.
#pragma once

#include <functional>
#include <memory>
#include <utility>

#include "trackbed/estimation/localization.h"
#include "trackbed/navigation/navigation_metrics.h"
#include "trackbed/robot/imu.h"
#include "trackbed/robot/stereo_rig.h"
#include "trackbed/runner/run_metrics.h"
#include "trackbed/scenario/scenario.h"
#include "trackbed/teach_repeat/teach_repeat.h"

namespace trackbed::runner {

/// One stereo pair as the robot's cameras saw it.
struct StereoFrame {
  std::int64_t index = 0;  ///< 0, 1, 2, … at the camera rate.
  double t_s = 0.0;
  const sim::GrayImage* left = nullptr;
  const sim::GrayImage* right = nullptr;
  Eigen::Isometry3d T_world_left;  ///< Ground truth of the left camera (OpenCV axes).
  Eigen::Isometry3d T_world_right;
  const robot::StereoRig* rig = nullptr;
  bool blackout = false;  ///< A camera fault blanked this pair (robot.stereo.blackouts_s).
  /// The encoders' last reading (counts since start), taken with this pair.
  std::int64_t ticks[2] = {0, 0};
};

/// The localization stack's estimates at one encoder sample (all T_world_body).
struct EstimateSample {
  double t_s = 0.0;
  Eigen::Isometry3d wheel_odometry, wheel_odometry_noslip, fused, ekf;
  bool has_camera = false;  ///< fused (and visual odometry) exist
  estimation::TrackSlip slip;
};

/// The stack's work on one stereo frame.
struct LocalizationFrame {
  double t_s = 0.0;
  bool camera_blackout = false;
  estimation::LocalizationFrameReport report;
  Eigen::Isometry3d visual_odometry;  ///< T_world_body after this frame
};

/// Observers of a run; any may be empty.
struct RunObservers {
  /// Every stereo frame's visual odometry and fusion (when the camera is on).
  std::function<void(const LocalizationFrame&)> on_localization_frame;
  /// Every stereo pair (when robot.stereo.enabled).
  std::function<void(const StereoFrame&)> on_stereo;
  /// Every encoder sample (ground truth and, when estimation.enabled, the estimates alongside).
  std::function<void(const RunSample&)> on_sample;
  /// Every IMU sample.
  std::function<void(const robot::ImuSample&)> on_imu;
  /// Every control step of closed-loop navigation (ground-truth pose, command, target).
  std::function<void(const navigation::NavigationLogEntry&)> on_navigation_step;
  /// Every camera frame of a teach & repeat repeat pass: its time and the command.
  std::function<void(const std::pair<double, teach_repeat::RepeatCommand>&)> on_repeat_step;
};

/// Builds observers member by member: out.X = f(a.X, b.X) for every observer X. The
/// one list of RunObservers' members, for code that wraps or combines observers.
template <class F>
RunObservers CombineObservers(const RunObservers& a, const RunObservers& b, F&& f) {
  RunObservers out;
  out.on_localization_frame = f(a.on_localization_frame, b.on_localization_frame);
  out.on_stereo = f(a.on_stereo, b.on_stereo);
  out.on_sample = f(a.on_sample, b.on_sample);
  out.on_imu = f(a.on_imu, b.on_imu);
  out.on_navigation_step = f(a.on_navigation_step, b.on_navigation_step);
  out.on_repeat_step = f(a.on_repeat_step, b.on_repeat_step);
  return out;
}

/// Runs one scenario in closed loop. With `repeater`, the repeat of teach & repeat
/// drives: it gets every left image and its command is held until the next one; the
/// run ends when it reports finished or lost. Throws std::invalid_argument for an
/// invalid scenario; a simulation that diverges (NaN, chassis through the
/// ground) ends early with completed = false and the reason, keeping what
/// was measured until then.
RunMetrics RunClosedLoop(const scenario::Scenario& scenario, const RunObservers& observers = {},
                         teach_repeat::Repeater* repeater = nullptr);

}  // namespace trackbed::runner
