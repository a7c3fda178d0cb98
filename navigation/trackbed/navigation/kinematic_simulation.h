// The paper's differential-drive simulation (Jung & Kim 2014, §3; docs/navigation.md's
// `kinematic` mode): the robot follows the commanded wheel speeds exactly (no slip, no
// dynamics), starts at the scene's start pose, and the navigator sees the true pose and
// the exact obstacle circles. Collision = the footprint disk overlapping an obstacle's
// physical circle, checked along the motion, not only at the control instants.
#pragma once

#include <functional>
#include <vector>

#include "trackbed/navigation/diff_drive.h"
#include "trackbed/navigation/navigation_metrics.h"
#include "trackbed/navigation/navigator.h"
#include "trackbed/navigation/obstacle_fields.h"

namespace trackbed::navigation {

struct KinematicSimulationOptions {
  /// The simulated robot (the paper's r = 0.2 m, W = 0.5 m, |φ̇| ≤ 25 rad/s). Not a key
  /// of this struct: a run takes the navigators' (`navigation.wheel_radius_m`, …).
  DiffDriveParams drive;
  /// Control period Δt [s], > 0 (the paper's 100 ms). Not a key of this struct: a run
  /// takes the navigators' (`navigation.control_period_s`).
  double control_period_s = 0.1;
  /// Success tolerances and the time limit [s] after which the run ends. Not keys: a run
  /// keeps the tolerances' defaults (0.1 m and 2°) and takes its `duration_s`.
  SuccessCriteria criteria;
  /// Footprint radius for collisions and clearance [m], >= 0. Not a key of this struct:
  /// a run sets it from `navigation.footprint_radius_m`.
  double footprint_radius_m = 0.35;
  /// Collision checks per control period along the exact arc, >= 1 (0.05 m apart at
  /// 5 m/s with the default).
  int substeps = 10;
  /// End the run at the first collision (status "collision").
  bool stop_on_collision = true;
  /// Called with each row as it is logged, in order (a run's progress); may be empty.
  /// Not a key.
  std::function<void(const NavigationLogEntry&)> on_row;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `navigation.kinematic`), read and written by the config archive
  /// (trackbed/common/archive.h); the other fields are set by the run (above).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("substeps", &substeps);
    a->Visit("stop_on_collision", &stop_on_collision);
  }
};

struct KinematicRun {
  std::vector<NavigationLogEntry> log;  ///< One row per control step, plus the last pose.
  NavigationMetrics metrics;
  std::vector<SubgoalRecord> subgoals;  ///< The navigator's sub-goals (may be empty).
};

/// Runs `navigator` (built for `scene.goal`) from `scene.start` until it reports a status
/// other than driving, a collision (if stop_on_collision) or the time limit. The last row
/// holds the final pose with a zero command unless the navigator ended the run. Throws
/// std::invalid_argument if the navigator's goal is not the scene's, OptionError for
/// invalid options.
KinematicRun RunKinematicSimulation(const NavigationScene& scene, Navigator& navigator,
                                    const KinematicSimulationOptions& options);

}  // namespace trackbed::navigation
