// Navigation scenes (see obstacle_fields.h).
#include "trackbed/navigation/obstacle_fields.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "trackbed/common/random.h"
#include "trackbed/common/units.h"

namespace trackbed::navigation {
namespace {

void AddWall(std::vector<Circle>* obstacles, Eigen::Vector2d a, Eigen::Vector2d b) {
  for (const Circle& c : WallCircles(a, b, kWallRadiusM, kWallSpacingM)) {
    obstacles->push_back(c);
  }
}

}  // namespace

NavigationScene RandomObstacleField(std::uint64_t seed, const RandomFieldOptions& options) {
  if (options.min_obstacles < 0 || options.max_obstacles < options.min_obstacles) {
    throw std::invalid_argument("RandomObstacleField: bad obstacle count range");
  }
  random::Generator rng(seed);
  NavigationScene scene;
  scene.name = "random_" + std::to_string(seed);
  const double bearing = options.max_bearing_rad * (2.0 * rng.Uniform() - 1.0);
  const double heading = -M_PI + 2.0 * M_PI * rng.Uniform();
  const int span = options.max_obstacles - options.min_obstacles + 1;
  const int count =
      options.min_obstacles + std::min(span - 1, static_cast<int>(span * rng.Uniform()));
  scene.goal = {options.goal_distance_m * std::cos(bearing),
                options.goal_distance_m * std::sin(bearing), heading};

  const Eigen::Vector2d start(scene.start.x, scene.start.y), goal(scene.goal.x, scene.goal.y);
  Eigen::Vector2d lo = start.cwiseMin(goal), hi = start.cwiseMax(goal);
  for (int axis = 0; axis < 2; ++axis) {
    const double side = hi[axis] - lo[axis];
    if (side < options.min_box_side_m) {
      const double mid = (hi[axis] + lo[axis]) / 2.0;
      lo[axis] = mid - options.min_box_side_m / 2.0;
      hi[axis] = mid + options.min_box_side_m / 2.0;
    }
  }
  for (int k = 0; k < count; ++k) {
    bool placed = false;
    for (int attempt = 0; attempt < 100000 && !placed; ++attempt) {
      Circle c;
      c.radius_m =
          options.min_radius_m + (options.max_radius_m - options.min_radius_m) * rng.Uniform();
      c.centre.x() = lo.x() + (hi.x() - lo.x()) * rng.Uniform();
      c.centre.y() = lo.y() + (hi.y() - lo.y()) * rng.Uniform();
      if (SurfaceDistance(start, c) >= options.keep_out_m &&
          SurfaceDistance(goal, c) >= options.keep_out_m) {
        scene.obstacles.push_back(c);
        placed = true;
      }
    }
    if (!placed) {
      throw std::invalid_argument("RandomObstacleField: no room for the obstacles (seed " +
                                  std::to_string(seed) + ")");
    }
  }
  return scene;
}

NavigationScene PaperSceneLeft() {
  return {"paper_left", {0, 0, 0}, {-5, 5, units::Radians(90.0)}, {Circle{{-2.5, 2.5}, 0.0}}};
}

NavigationScene PaperSceneRight() {
  return {"paper_right", {0, 0, 0}, {5, 5, units::Radians(90.0)}, {Circle{{2.5, 2.5}, 0.0}}};
}

NavigationScene UTrapScene() {
  NavigationScene s{"u_trap", {0, 0, 0}, {10, 0, 0}, {}};
  AddWall(&s.obstacles, {6, -2}, {6, 2});
  AddWall(&s.obstacles, {3, 2}, {5.5, 2});
  AddWall(&s.obstacles, {3, -2}, {5.5, -2});
  return s;
}

NavigationScene NarrowGapScene() {
  NavigationScene s{"narrow_gap", {0, 0, 0}, {10, 0, 0}, {}};
  AddWall(&s.obstacles, {5, 0.8}, {5, 6});
  AddWall(&s.obstacles, {5, -0.8}, {5, -6});
  return s;
}

NavigationScene GoalBesideWallScene() {
  NavigationScene s{"goal_beside_wall", {0, 0, 0}, {10, 0, units::Radians(90.0)}, {}};
  AddWall(&s.obstacles, {10.8, -4}, {10.8, 4});
  return s;
}

NavigationScene NarrowCorridorScene() {
  NavigationScene s{"narrow_corridor", {0, 0, 0}, {11, 0.3, 0}, {}};
  AddWall(&s.obstacles, {3, 0.9}, {9, 0.9});
  AddWall(&s.obstacles, {3, -0.9}, {9, -0.9});
  return s;
}

std::vector<NavigationScene> TrapScenes() {
  return {UTrapScene(), NarrowGapScene(), GoalBesideWallScene(), NarrowCorridorScene()};
}

NavigationScene GoalInObstacleScene() {
  return {"goal_in_obstacle", {0, 0, 0}, {6, 0, 0}, {Circle{{6, 0}, 0.5}}};
}

NavigationScene EnclosedGoalScene() {
  NavigationScene s{"enclosed_goal", {0, 0, 0}, {6, 0, 0}, {}};
  const double ring = 1.5;
  const int links = static_cast<int>(std::ceil(2.0 * M_PI * ring / kWallSpacingM));
  for (int k = 0; k < links; ++k) {
    const double a = 2.0 * M_PI * k / links;
    s.obstacles.push_back(Circle{{6 + ring * std::cos(a), ring * std::sin(a)}, kWallRadiusM});
  }
  return s;
}

}  // namespace trackbed::navigation
