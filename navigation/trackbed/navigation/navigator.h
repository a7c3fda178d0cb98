// The common interface of the point-to-point navigation methods (docs/navigation.md):
// Gauss–Newton with sub-goals, the potential field and the dynamic window. Each is
// called once per control period with the robot's pose and the obstacles known now
// (exact circles in kinematic mode, clustered range-sensor hits in closed loop), and
// returns wheel speeds and a status. A run ends with a clear status, never a hang: the
// goal is reached, the goal lies inside an obstacle, or no progress was made for a
// configurable time — the same checks for every method (NavigationChecks, built from
// goal_checker.h and progress_checker.h).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "trackbed/common/option_error.h"
#include "trackbed/navigation/circle_obstacle.h"
#include "trackbed/navigation/diff_drive.h"
#include "trackbed/navigation/goal_checker.h"
#include "trackbed/navigation/navigation_setup.h"
#include "trackbed/navigation/progress_checker.h"
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

/// The checks that end every navigator's run, kept out of the methods (as nav2 keeps its
/// goal and progress checkers out of its controllers) so that all of them end a run by
/// one rule, in one order: a goal inside an obstacle ends it at once (kGoalInObstacle);
/// then the goal tolerances (kReached); then, after the method's command, lack of
/// progress (kStalled, which replaces that command by zero). Once the run has ended the
/// status stays and the command is zero, with the goal as its target.
class NavigationChecks {
 public:
  /// Takes the goal tolerances and control period from `setup` (validate it first).
  /// Throws OptionError naming the first invalid field of `progress`, without a prefix:
  /// navigators validate it as ValidatedOptions("progress", …) before.
  NavigationChecks(const NavigationSetup& setup, const ProgressCheckerOptions& progress,
                   const Pose2& goal);

  /// One control period. While the run goes on, `drive(&command)` fills in the method's
  /// command, which it receives zero with the goal as its target; it is not called once
  /// the run has ended.
  template <typename Drive>
  NavigationCommand Update(const Pose2& pose, const std::vector<Circle>& obstacles, Drive&& drive) {
    NavigationCommand command = CheckGoal(pose, obstacles);
    if (command.status != NavigationStatus::kDriving) return command;
    drive(&command);
    CheckProgress(pose, &command);
    return command;
  }

  NavigationStatus status() const { return status_; }

 private:
  /// The goal checks; a zero command toward the goal with the status they leave.
  NavigationCommand CheckGoal(const Pose2& pose, const std::vector<Circle>& obstacles);
  /// The progress check on the method's `command`; sets its status.
  void CheckProgress(const Pose2& pose, NavigationCommand* command);

  GoalChecker goal_checker_;
  ProgressChecker progress_checker_;
  double control_period_s_;
  NavigationStatus status_ = NavigationStatus::kDriving;
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
  /// The robot's body twist as measured just before the next Update (closed loop: from
  /// the pose it believes). A method that models the robot's dynamics starts from it
  /// (the dynamic window); the others ignore it. Without it, a method takes its own
  /// last command for the robot's twist (kinematic mode, where the command is exact).
  virtual void SetMeasuredTwist(const BodyTwist& /*twist*/) {}

  /// The method's name as MakeNavigator accepts it.
  virtual const char* method() const = 0;
  /// The goal pose.
  virtual const Pose2& goal() const = 0;
  /// Sub-goals created so far (empty for methods without them).
  virtual std::vector<SubgoalRecord> subgoals() const { return {}; }
};

}  // namespace trackbed::navigation
