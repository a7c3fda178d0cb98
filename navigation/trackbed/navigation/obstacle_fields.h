// Navigation scenes as pure functions: the paper's two scenes (Jung & Kim 2014, §3),
// seeded random multi-obstacle fields and potential-field traps (docs/navigation.md). Every scene
// starts at [0 0 0°]. Walls are chains of circles of radius 0.1 m, 0.5 m apart
// (≤ d_max = 1 m), so the avoider never sees a gap its safety circles would miss and
// the footprint (0.7 m across) cannot slip between two links.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "trackbed/navigation/circle_obstacle.h"
#include "trackbed/navigation/diff_drive.h"

namespace trackbed::navigation {

/// A start pose, a goal pose and obstacle circles, all in the world frame.
struct NavigationScene {
  std::string name;
  Pose2 start;
  Pose2 goal;
  std::vector<Circle> obstacles;
};

/// Radius [m] and link spacing [m] of the walls built by the trap scenes.
inline constexpr double kWallRadiusM = 0.1;
inline constexpr double kWallSpacingM = 0.5;

struct RandomFieldOptions {
  /// Distance from the start to the goal [m].
  double goal_distance_m = 10.0;
  /// The goal's bearing from the start is uniform in ±this [rad].
  double max_bearing_rad = M_PI / 4.0;
  /// Obstacle count, uniform in [min_obstacles, max_obstacles].
  int min_obstacles = 5;
  int max_obstacles = 10;
  /// Obstacle radius, uniform in [min_radius_m, max_radius_m).
  double min_radius_m = 0.2;
  double max_radius_m = 0.5;
  /// The placement box is the axis-aligned box spanned by start and goal, each side
  /// widened symmetrically about its centre to at least this [m] so that it never
  /// degenerates (a goal straight ahead spans a 10 m × 0 m box).
  double min_box_side_m = 4.0;
  /// No obstacle's *surface* within this distance of the start or the goal [m]
  /// (|centre − point| − radius ≥ keep_out_m).
  double keep_out_m = 1.5;
};

/// The seeded random field for `seed`: start [0 0 0°]; goal at goal_distance_m with a
/// uniform bearing in ±max_bearing_rad and a uniform heading in [−π, π); a uniform count
/// of obstacles, each with a uniform radius and a centre uniform in the placement box,
/// redrawn (radius and centre) until it keeps out of start and goal. Obstacles may
/// overlap one another. Draw order: bearing, heading, count, then (radius, x, y) per
/// attempt. Identical across platforms and standard libraries for the same seed.
NavigationScene RandomObstacleField(std::uint64_t seed, const RandomFieldOptions& options = {});

/// Jung & Kim 2014 fig. 5: goal [−5 5 90°], point obstacle at [−2.5 2.5].
NavigationScene PaperSceneLeft();
/// Jung & Kim 2014 figs. 6–7: goal [5 5 90°], point obstacle at [2.5 2.5].
NavigationScene PaperSceneRight();

/// U-shaped trap opening toward the robot: back wall x = 6 m (y ∈ [−2, 2]), arms along
/// y = ±2 m from x = 3 m to 6 m; goal [10 0 0°] behind it.
NavigationScene UTrapScene();
/// A wall across the way (x = 5 m, y ∈ [−6, 6]) with a 1.6 m gap between link centres
/// (1.4 m between surfaces, narrower than twice the potential field's influence range,
/// wide enough for the 0.7 m footprint); goal [10 0 0°].
NavigationScene NarrowGapScene();
/// Goal [10 0 90°] 0.8 m in front of a wall (x = 10.8 m, y ∈ [−4, 4]): within the
/// repulsion range, the plain field's "goal non-reachable" case.
NavigationScene GoalBesideWallScene();
/// A corridor 1.8 m wide between link centres (walls y = ±0.9 m, x ∈ [3, 9]) with the
/// goal [11 0.3 0°] beyond its end.
NavigationScene NarrowCorridorScene();
/// The four traps, in the order above.
std::vector<NavigationScene> TrapScenes();

/// Bad input: goal [6 0 0°] inside an obstacle of radius 0.5 m centred on it.
NavigationScene GoalInObstacleScene();
/// Unreachable goal: goal [6 0 0°] enclosed by a ring of radius 1.5 m of wall links.
NavigationScene EnclosedGoalScene();

}  // namespace trackbed::navigation
