// The closed loop: the simulated world and robot on one clock, sensors sampled at
// their rates, the localization stack on the robot's own sensors, a Commander driving
// the tracks, ground truth scored as the run goes and the run folder written while it
// goes. A ClosedLoop owns one run and can be driven from outside, one control period
// at a time: `trackbed run` is a loop over Step().
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/estimation/localization.h"
#include "trackbed/robot/imu.h"
#include "trackbed/robot/range_sensor.h"
#include "trackbed/runner/commander.h"
#include "trackbed/runner/robot_build.h"
#include "trackbed/runner/run_metrics.h"
#include "trackbed/runner/run_observers.h"
#include "trackbed/scenario/scenario.h"
#include "trackbed/sim/track_marks.h"

namespace trackbed::runner {

/// How a ClosedLoop is set up beyond its scenario.
struct ClosedLoopOptions {
  /// The run folder (created if needed; an earlier run's files there are replaced).
  /// Empty: no files are written, Finish() only returns the metrics.
  std::filesystem::path dir;
  /// What drives the run; null: the scenario's own — closed-loop navigation when
  /// `navigation.enabled`, else the `drive` section. A commander given here replaces
  /// the `drive` section (which then needs only a valid `rate_hz`) and excludes
  /// `navigation.enabled`.
  std::unique_ptr<Commander> commander;
  /// Called after the run folder's own observers.
  RunObservers observers;
  /// Step() returns copies of the stereo pairs taken in its period.
  bool step_images = false;
  /// The robot as built and its given calibration, when already drawn for this
  /// scenario (BuildRunRobot); none: drawn at Start().
  std::optional<RobotBuild> robot;
  /// The robot's track marks to continue (a teach pass's, for its repeat pass), with
  /// `scene.appearance.track_marks`; null: a new record.
  std::shared_ptr<sim::TrackMarks> track_marks;
};

/// One encoder reading: counts since the start, left and right.
struct EncoderReading {
  double t_s = 0.0;
  std::int64_t ticks[2] = {0, 0};
};

/// A stereo pair a Step took, as the robot's cameras gave it.
struct StereoImages {
  double t_s = 0.0;
  GrayImage left, right;
};

/// What the sensors produced in one Step, and the truth at its end.
struct StepResult {
  double t_s = 0.0;  ///< simulation time at the end of the step [s]
  std::vector<EncoderReading> encoders;
  std::vector<robot::ImuSample> imu;
  std::vector<robot::RangeScanSample> scans;
  std::int64_t stereo_frames = 0;    ///< pairs taken in this step
  std::vector<StereoImages> stereo;  ///< the pairs, with ClosedLoopOptions::step_images
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();  ///< ground truth at the end
};

/// Sizes of what a run holds in memory beyond its fixed state (ClosedLoop::held_sizes).
struct HeldSizes {
  std::size_t scoring_window_poses = 0;  ///< poses in the estimator scores' 10 m windows
  std::size_t plot_points = 0;           ///< points of every plot path and series
  std::size_t largest_plot_series = 0;   ///< points of the largest one
  std::size_t icr_fit_groups = 0;        ///< the ICR fit's jackknife groups (at most 40)
};

/// One closed-loop run. Not copyable. Start() once, Step() until done(), Finish() once.
/// A simulation that diverges (NaN, chassis through the ground) ends the run early with
/// completed = false and the reason, keeping what was measured until then. Any
/// exception leaves a metrics.json that says why the run stopped (when a folder is
/// written) and is rethrown.
class ClosedLoop {
 public:
  /// Throws std::invalid_argument for an invalid scenario.
  explicit ClosedLoop(const scenario::Scenario& scenario, ClosedLoopOptions options = {});
  ClosedLoop(const ClosedLoop&) = delete;
  ClosedLoop& operator=(const ClosedLoop&) = delete;
  ~ClosedLoop();

  /// Writes the resolved scenario into the run folder and builds the world, the robot,
  /// its sensors and its software.
  void Start();
  /// One control period: simulates up to and including the commander's next call and
  /// the physics step after it. Returns what the sensors produced meanwhile, in a buffer
  /// the loop reuses: valid until the next Step() (so a long run allocates nothing per
  /// step).
  const StepResult& Step();
  /// The run has ended (duration reached, the commander stopped it, a stall, a failure).
  bool done() const;
  /// The robot's localization stack, up to date with every sample taken so far; null
  /// when estimation is off. Valid until the next Step() or Finish().
  const estimation::LocalizationStack* localization();
  /// What the run holds that a longer run could make larger (tests of long runs):
  /// the scores' drift windows and the plots' points. Between Start() and Finish().
  HeldSizes held_sizes();
  /// Scores `T_world_body` as estimator `name`'s estimate at the loop's current time
  /// (the end of the last Step(), or t = 0 after Start()) against ground truth then,
  /// beside the stack's estimators: metrics.json `estimators.<name>`, `<name>.tum` and
  /// the plots. Throws std::invalid_argument (one line) for a name that is empty, not
  /// made of letters, digits, '_' and '-', or taken (a built-in estimator, ground_truth);
  /// for a matrix that is not a rigid transform; for a second estimate of the name at
  /// the same time. Throws std::logic_error before Start() or after Finish().
  void ReportEstimate(const std::string& name, const Eigen::Matrix4d& T_world_body);
  /// Writes the rest of the run folder (plots, metrics.json) and returns the metrics.
  RunMetrics Finish();
  /// Start(), Step() until done(), Finish().
  RunMetrics Run();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

/// `scenario`'s robot as built and its given calibration, with the straight calibration
/// run (wheel_calibration_run.h) run in closed loop when the imperfections ask for it.
RobotBuild BuildRunRobot(const scenario::Scenario& scenario);

/// Runs `scenario` in closed loop without a run folder, with `observers`.
RunMetrics RunClosedLoop(const scenario::Scenario& scenario, const RunObservers& observers = {});

}  // namespace trackbed::runner
