// The common interface of the point-to-point navigation methods (issue 5):
// Gauss–Newton with sub-goals, the potential field and the dynamic window. Each is
// called once per control period with the robot's pose and the obstacles known now
// (exact circles in kinematic mode, clustered range-sensor hits in closed loop), and
// returns wheel speeds and a status. A run ends with a clear status, never a hang: the
// goal is reached, the goal lies inside an obstacle, or no progress was made for a
// configurable time.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "trackbed/common/option_error.h"
#include "trackbed/navigation/circle_obstacle.h"
#include "trackbed/navigation/diff_drive.h"
#include "trackbed/navigation/subgoal_planner.h"

namespace trackbed::navigation {

enum class NavigationStatus {
  kDriving,         ///< On the way.
  kReached,         ///< Within both goal tolerances: the command is zero.
  kGoalInObstacle,  ///< The goal lies inside an obstacle's physical circle.
  kStalled,         ///< No progress toward the goal for `stall_time_s`: unreachable, or
                    ///< the method is trapped.
};

/// "driving", "reached", "goal_in_obstacle", "stalled".
const char* NavigationStatusName(NavigationStatus status);

/// One control step's output.
struct NavigationCommand {
  BodyTwist twist;     ///< Body twist of `wheels`.
  WheelSpeeds wheels;  ///< Wheel speeds after proportional saturation [rad/s].
  Eigen::Vector2d target = Eigen::Vector2d::Zero();  ///< Active target (goal or sub-goal).
  bool subgoal_active = false;
  NavigationStatus status = NavigationStatus::kDriving;
};

struct ProgressOptions {
  /// A run with no progress toward the goal for this long [s] ends as kStalled, > 0.
  double stall_time_s = 30.0;
  /// "Progress" = the best distance to the goal so far shrinking by at least this [m], > 0.
  double min_progress_m = 0.1;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;
};

/// Detects lack of progress toward the goal. The clock runs only while the robot is
/// farther than the goal position tolerance (the final turn is not "no progress").
class ProgressMonitor {
 public:
  explicit ProgressMonitor(const ProgressOptions& options);
  ProgressMonitor(const ProgressMonitor&) = delete;
  ProgressMonitor& operator=(const ProgressMonitor&) = delete;

  /// Adds one control period of `dt_s` [s] at distance `distance_m` from the goal;
  /// returns true once stalled (and from then on).
  bool Update(double distance_m, double tolerance_m, double dt_s);

 private:
  ProgressOptions options_;
  double best_m_ = -1.0;
  double since_s_ = 0.0;
  bool stalled_ = false;
};

/// Validates `options` with its field names under `prefix` (OptionError says
/// `prefix.field`) and returns it: for constructors' member initialisers.
template <typename Options>
const Options& ValidatedOptions(const char* prefix, const Options& options) {
  option_check::Nested(prefix, options);
  return options;
}

/// A point-to-point navigation method with its goal. Stateful: not copyable.
class Navigator {
 public:
  Navigator() = default;
  Navigator(const Navigator&) = delete;
  Navigator& operator=(const Navigator&) = delete;
  virtual ~Navigator() = default;

  /// One control period: the robot's pose and the obstacles known now, both in the world
  /// frame. Once the status is not kDriving it stays so and the command is zero.
  virtual NavigationCommand Update(const Pose2& pose, const std::vector<Circle>& obstacles) = 0;

  /// The method's name as MakeNavigator accepts it.
  virtual const char* method() const = 0;
  /// The goal pose.
  virtual const Pose2& goal() const = 0;
  /// Sub-goals created so far (empty for methods without them).
  virtual std::vector<SubgoalRecord> subgoals() const { return {}; }
};

}  // namespace trackbed::navigation
