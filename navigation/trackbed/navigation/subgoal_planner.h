// Sub-goal switching for obstacle avoidance (Jung & Kim 2014, §2.4), extended to
// several obstacles.
//
// The paper (point obstacles): the robot and each obstacle carry a circle of radius
// d_max (the safety radius, 1 m). Avoidance triggers only when the two circles meet
// (distance ≤ 2·d_max) *and* the robot's driving direction θ_R points into the
// obstacle's circle:
//   - robot outside the obstacle's circle: θ1 − θ2 < θ_R < θ1 + θ2, θ1 the bearing of
//     the obstacle (eq. 13), θ2 = asin(d_max / dist); the sub-goal lies on a tangent,
//     robot + 1.2·(tangent point − robot);
//   - robot inside it: the lines to the two intersection points of the robot's and the
//     obstacle's circles replace the tangents (θ3 ± θ4), and the sub-goal is
//     robot + 1.2·(intersection point − robot).
// Of the two candidates the one nearer the goal is taken (eq. 20); the robot drives to
// it like to a goal and switches back to the goal when it is reached and nothing blocks.
//
// How a physical radius combines with d_max. An obstacle of physical radius R carries a
// safety circle of radius R + d_max (the robot's centre should stay d_max away from its
// surface); the robot carries a circle of radius d_max as in the paper. So the circles
// meet at dist ≤ 2·d_max + R, θ2 = asin((R + d_max)/dist), and the intersection points
// are those of circle(robot, d_max) and circle(centre, R + d_max). R = 0 is the paper.
//
// Our readings and extensions (each one documented where it is implemented):
//  1. Driving direction. θ_R is tested only when the robot is about to translate, i.e.
//     when its heading is within `alignment_band_rad` of the bearing to the active
//     target (the Gauss–Newton controller drives only then, turning in place before).
//     A heading swept during a turn in place is not a driving direction.
//  2. Multi-obstacle rule (the paper's stated future work). Obstacles whose safety
//     circles overlap form a cluster (transitively): the robot's centre cannot pass
//     between them without entering a safety circle. The obstacle that triggers is the
//     nearest blocking one (smallest surface distance); the sub-goal is placed on the
//     extreme tangent (or intersection line) of its *whole cluster* as seen from the
//     robot: the union of the per-circle cones [θ1 − θ2, θ1 + θ2] grown from the
//     blocking circle's cone, whose two edges play the role of the paper's two tangents.
//     For one circle this is exactly the paper's construction. If the union closes
//     around the robot (≥ 2π) there is no way around: no sub-goal is made and the
//     result says so (`no_way_around`). `cluster_obstacles = false` applies the paper's
//     single-circle rule to the nearest blocking circle instead.
//  3. Sub-goal safety. A candidate is free when its footprint (`robot_radius_m`) overlaps
//     no obstacle and the straight way to it enters no safety circle of an obstacle
//     outside the group planned around (one the robot is already inside excepted). A
//     free candidate is taken before one that is not; between two free (or two blocked)
//     candidates the paper's rule decides.
//  4. While a sub-goal is active, the obstacles it was made for (its group) do not
//     trigger again: its tangent already clears them, and re-triggering on them would
//     creep around the circle. Another obstacle that blocks the way to the sub-goal
//     triggers a new plan for the union of both groups (their cones joined as in 2).
//  5. Target-aware blocking. An obstacle whose centre lies beyond the active target
//     (its projection on the robot→target line is past the target) and which the
//     straight segment to the target clears by `robot_radius_m` does not block: the
//     robot stops before reaching it.
//  6. Goal-nearby correction (in the spirit of Ge & Cui 2000 for potential fields):
//     an obstacle whose surface is nearer the goal than d_max + `goal_margin_m` gets
//     the smaller margin (surface distance − goal_margin_m, at least `robot_radius_m`)
//     so that the goal stays outside every safety circle and can be reached. Far from
//     the goal (all of the paper's scenes, all random fields) nothing changes.
//  7. Minimum sub-goal distance. A sub-goal is placed at scale·max(ℓ, d_max) along its
//     line, ℓ the distance to the tangent point (the intersection points are at d_max,
//     so the inside case is unchanged). Without it a robot standing just outside a
//     safety circle — where the previous sub-goal leaves it — gets a tangent of
//     vanishing length, and the sub-goals creep around the circle in ever smaller steps
//     (in the paper's own right-hand scene the goal is still blocked from the first
//     sub-goal). At the paper's trigger distances (ℓ ≥ d_max for dist ≥ √2·d_max) the
//     placement is the paper's 1.2·ℓ.
//  8. Side memory (as bug algorithms keep their direction around an obstacle). After a
//     plan around a group, the side taken (left/right) is remembered for those
//     obstacles; a later plan triggered by one of them takes the same side while that
//     candidate is free. Without it, a robot between two clusters was sent around one,
//     found its way blocked by the other, and was sent back — for ever. The memory is
//     forgotten once the goal is the target and nothing blocks the way to it.
// Ties between candidates whose distances to the goal differ by less than 1 mm (the
// paper's collinear scenes) go to the left, counter-clockwise side as seen from the
// robot.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "trackbed/common/units.h"
#include "trackbed/navigation/circle_obstacle.h"
#include "trackbed/navigation/diff_drive.h"

namespace trackbed::navigation {

/// The two candidate sub-goals for one circle. "Left" is the counter-clockwise side
/// as seen from the robot looking at the obstacle.
struct SubgoalPair {
  Eigen::Vector2d left = Eigen::Vector2d::Zero();        ///< robot + scale·(left_point − robot)
  Eigen::Vector2d right = Eigen::Vector2d::Zero();       ///< robot + scale·(right_point − robot)
  Eigen::Vector2d left_point = Eigen::Vector2d::Zero();  ///< Tangent/intersection point.
  Eigen::Vector2d right_point = Eigen::Vector2d::Zero();  ///< Tangent/intersection point.
};

/// Robot outside the circle (centre, `safety_radius_m`): the two tangent points from the
/// robot and the sub-goals robot + scale·(tangent − robot). Empty when the robot is on
/// or inside the circle. All positions in the world frame [m].
std::optional<SubgoalPair> TangentSubgoals(const Eigen::Vector2d& robot,
                                           const Eigen::Vector2d& centre, double safety_radius_m,
                                           double scale = 1.2);

/// Robot inside the circle (centre, `safety_radius_m`): the two intersection points of
/// the robot's circle (radius `robot_circle_radius_m`) with it and the sub-goals
/// robot + scale·(intersection − robot). Empty when the circles do not intersect in two
/// points.
std::optional<SubgoalPair> IntersectionSubgoals(const Eigen::Vector2d& robot,
                                                double robot_circle_radius_m,
                                                const Eigen::Vector2d& centre,
                                                double safety_radius_m, double scale = 1.2);

/// The directions from the robot that point into an obstacle's circle.
struct AvoidanceCone {
  enum class Kind {
    kTangent,       ///< Robot outside the obstacle's circle: θ1 ± θ2, edges at tangents.
    kIntersection,  ///< Robot inside: θ3 ± θ4, edges at the circles' intersection points.
    kHalfPlane,     ///< Robot inside a circle that lies within its own circle (possible
                    ///< only for shrunk goal-nearby margins): ±90°, edges at d_max.
    kEnclosing,     ///< Robot inside the obstacle's physical circle: every direction.
  };
  Kind kind = Kind::kTangent;
  double direction_rad = 0.0;    ///< θ1 (θ3): bearing of the obstacle's centre.
  double half_width_rad = 0.0;   ///< θ2 (θ4) [rad]; π for kEnclosing.
  double edge_distance_m = 0.0;  ///< Distance from the robot to the edge points.
};

/// The cone of `obstacle` (physical circle) inflated by `obstacle_margin_m`, seen from a
/// robot whose own circle has radius `robot_circle_radius_m`.
AvoidanceCone AvoidanceConeOf(const Eigen::Vector2d& robot, double robot_circle_radius_m,
                              const Circle& obstacle, double obstacle_margin_m);

/// The paper's trigger for one obstacle with safety radius d_max = `safety_radius_m`:
/// the circles meet (distance ≤ 2·d_max + R) and the robot's heading points strictly
/// into the obstacle's cone. A robot inside the physical circle is always blocked.
bool Blocks(const Pose2& robot, const Circle& obstacle, double safety_radius_m);

/// Cluster labels (0, 1, …, in order of first appearance): obstacles i and j share a
/// label when their safety circles (radius R + margin) overlap, transitively.
/// `margins_m` has one margin per obstacle.
std::vector<int> ClusterLabels(const std::vector<Circle>& obstacles,
                               const std::vector<double>& margins_m);

struct SubgoalOptions {
  /// d_max [m], > 0: the safety radius of the robot's and the obstacles' circles. Not a
  /// key of this struct: a run sets it from the scenario's `navigation.safety_radius_m`,
  /// which also spaces the walls' circles and the scan clustering's.
  double safety_radius_m = 1.0;
  /// Sub-goal placement factor along the tangent/intersection line, >= 1 (paper: 1.2);
  /// the sub-goal is at scale·max(ℓ, d_max) (rule 7).
  double subgoal_scale = 1.2;
  /// A sub-goal counts as reached within this distance [m], > 0.
  double reached_distance_m = 0.2;
  /// Obstacles are tested only when the heading is within this angle of the bearing to
  /// the active target [rad], in (0, π] (rule 1; match the controller's heading band).
  double alignment_band_rad = units::Radians(5.0);
  /// Plan around whole clusters of overlapping safety circles (rule 2); false applies
  /// the paper's single-circle rule to the nearest blocking circle.
  bool cluster_obstacles = true;
  /// Radius of the robot's footprint [m], >= 0, for sub-goal safety (rules 3, 5, 6). Not
  /// a key of this struct: a run sets it from the scenario's footprint
  /// (`navigation.footprint_radius_m`; closed loop: at least the hull's half diagonal).
  double robot_radius_m = 0.35;
  /// Goal-nearby correction (rule 6): the goal stays this far outside every safety
  /// circle [m], >= 0.
  double goal_margin_m = 0.1;
  /// A sensed obstacle belongs to the active sub-goal's group when its centre is within
  /// a group circle's radius plus this distance [m], > 0 (tolerates re-sensing).
  double match_distance_m = 0.25;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md,
  /// `navigation.subgoal`), read and written by the config archive
  /// (trackbed/common/archive.h); safety_radius_m and robot_radius_m are set by the
  /// run (above).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("subgoal_scale", &subgoal_scale);
    a->Visit("reached_distance_m", &reached_distance_m);
    a->Visit("alignment_band_rad", &alignment_band_rad);
    a->Visit("cluster_obstacles", &cluster_obstacles);
    a->Visit("goal_margin_m", &goal_margin_m);
    a->Visit("match_distance_m", &match_distance_m);
  }
};

/// One sub-goal, kept for plots and metrics.
struct SubgoalRecord {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();      ///< The sub-goal [m].
  Eigen::Vector2d created_from = Eigen::Vector2d::Zero();  ///< Robot position then [m].
  Eigen::Vector2d edge_point = Eigen::Vector2d::Zero();    ///< Its tangent/intersection point.
  int group_size = 1;                                      ///< Obstacles it was planned around.
  bool left = true;                                        ///< Counter-clockwise side.
  bool reached = false;  ///< The robot came within reached_distance_m of it.
};

/// What to drive to now.
struct ActiveTarget {
  /// The goal, or the sub-goal with heading = its bearing from where it was created.
  Pose2 pose;
  bool subgoal_active = false;
  bool new_subgoal = false;    ///< A sub-goal was created in this update.
  bool no_way_around = false;  ///< Blocked, but the blocking group closes around the robot.
  int blocking_obstacle = -1;  ///< Index of the obstacle that triggered (this update), or −1.
};

/// The per-obstacle margins actually used (rule 6): d_max, or less for obstacles near
/// the goal.
std::vector<double> SafetyMargins(const std::vector<Circle>& obstacles, const Eigen::Vector2d& goal,
                                  const SubgoalOptions& options);

/// Keeps the active target (goal or sub-goal) from step to step. Stateful: not copyable.
class SubgoalSwitcher {
 public:
  /// Validates `options` (throws OptionError).
  SubgoalSwitcher(const SubgoalOptions& options, const Pose2& goal);
  SubgoalSwitcher(const SubgoalSwitcher&) = delete;
  SubgoalSwitcher& operator=(const SubgoalSwitcher&) = delete;

  /// One control step: the pose (world frame) and the obstacles currently known.
  ActiveTarget Update(const Pose2& pose, const std::vector<Circle>& obstacles);

  /// Every sub-goal created so far, in order.
  const std::vector<SubgoalRecord>& subgoals() const { return subgoals_; }
  const Pose2& goal() const { return goal_; }

 private:
  SubgoalOptions options_;
  Pose2 goal_;
  bool active_ = false;
  Pose2 subgoal_;
  std::vector<Circle> group_;       // the obstacles the active sub-goal was planned around
  std::vector<Circle> side_group_;  // obstacles passed on side `side_left_` (rule 8)
  bool side_left_ = true;
  std::vector<SubgoalRecord> subgoals_;
};

}  // namespace trackbed::navigation
