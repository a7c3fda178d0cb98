// Per-step navigation logs and the run metrics computed from them (docs/navigation.md; they go to
// metrics.json under `navigation` and navigation.csv). Pure functions over the log, so
// the kinematic simulation and the closed-loop runner compute them the same way.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "trackbed/common/units.h"
#include "trackbed/navigation/diff_drive.h"

namespace trackbed::navigation {

/// One control step. The pose is the (true) pose at t_s; the command is what the
/// navigator returned then and is held until the next row.
struct NavigationLogEntry {
  double t_s = 0.0;
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0;
  double v_mps = 0.0, yaw_rate_radps = 0.0;
  double left_radps = 0.0, right_radps = 0.0;
  double target_x_m = 0.0, target_y_m = 0.0;
  bool subgoal_active = false;
  /// Distance from the footprint's edge to the nearest obstacle surface [m], negative on
  /// overlap, +infinity without obstacles: the smallest value over the motion that ended
  /// at this row (the pose itself for the first row).
  double clearance_m = 0.0;
};

/// What counts as success (docs/navigation.md): within both tolerances of the goal pose, no
/// collision, not later than the time limit.
struct SuccessCriteria {
  double position_tolerance_m = 0.1;
  double heading_tolerance_rad = units::Radians(2.0);
  double time_limit_s = 120.0;
};

struct NavigationMetrics {
  bool success = false;
  /// How the run ended: a NavigationStatusName, "collision" or "time_limit".
  std::string status;
  /// First time within both goal tolerances [s], for successful runs only.
  std::optional<double> time_to_goal_s;
  double duration_s = 0.0;               ///< Time of the last row [s].
  double path_length_m = 0.0;            ///< Polyline through the logged positions.
  double final_position_error_m = 0.0;   ///< At the last row.
  double final_heading_error_deg = 0.0;  ///< |goal yaw − yaw| at the last row, in [0, 180].
  double min_clearance_m = 0.0;          ///< Smallest clearance_m (+inf without obstacles).
  double mean_clearance_m = 0.0;         ///< Mean of the rows' clearance_m.
  int collisions = 0;                    ///< See CountCollisions.
  double integrated_abs_jerk = 0.0;      ///< See IntegratedAbsJerk [m/s²].
  int subgoals = 0;                      ///< Sub-goals created.
};

/// Sum of the distances between consecutive logged positions [m].
double PathLength(const std::vector<NavigationLogEntry>& log);

/// Collision events: maximal runs of consecutive rows with clearance_m < 0 (one contact
/// that lasts several steps is one event).
int CountCollisions(const std::vector<NavigationLogEntry>& log);

/// ∫|jerk| dt of the forward motion, as nav2's controller benchmark scores smoothness:
/// with the logged forward speeds v_k at times t_k, a_k = (v_k − v_{k−1})/(t_k − t_{k−1})
/// and j_k = (a_k − a_{k−1})/(t_k − t_{k−1}); the integral is Σ_k |j_k|·(t_k − t_{k−1})
/// [m/s²] over k ≥ 2. Rows with equal times are skipped. 0 for fewer than 3 rows.
double IntegratedAbsJerk(const std::vector<NavigationLogEntry>& log);

/// All metrics of a run. `status` is how the run ended, `subgoals` how many sub-goals
/// were created. Throws std::invalid_argument (naming the function) for an empty log.
NavigationMetrics ComputeNavigationMetrics(const std::vector<NavigationLogEntry>& log,
                                           const Pose2& goal, const SuccessCriteria& criteria,
                                           const std::string& status, int subgoals);

}  // namespace trackbed::navigation
