// The scenario's navigation section as the navigation library's inputs (see
// navigation_scenario.h).
#include "trackbed/runner/navigation_scenario.h"

#include <cmath>
#include <stdexcept>

#include "trackbed/common/units.h"

namespace trackbed::runner {
namespace {

navigation::DiffDriveParams DriveOf(const scenario::NavigationSpec& n) {
  navigation::DiffDriveParams d;
  d.wheel_radius_m = n.wheel_radius_m;
  d.wheel_separation_m = n.wheel_separation_m;
  d.max_wheel_speed_radps = n.max_wheel_speed_radps;
  return d;
}

}  // namespace

navigation::NavigationScene NavigationSceneOf(const scenario::Scenario& scenario) {
  const scenario::NavigationSpec& n = scenario.navigation;
  navigation::NavigationScene scene;
  if (n.field == "none") {
    scene.name = scenario.scene.name;
    const scenario::StartPose& s = scenario.robot.start;
    scene.start = {s.x_m, s.y_m, units::Radians(s.yaw_deg)};
    scene.goal = {n.goal.x_m, n.goal.y_m, units::Radians(n.goal.yaw_deg)};
  } else if (n.field == "random") {
    scene = navigation::RandomObstacleField(n.field_seed);
  } else if (n.field == "paper_left") {
    scene = navigation::PaperSceneLeft();
  } else if (n.field == "paper_right") {
    scene = navigation::PaperSceneRight();
  } else if (n.field == "u_trap") {
    scene = navigation::UTrapScene();
  } else if (n.field == "narrow_gap") {
    scene = navigation::NarrowGapScene();
  } else if (n.field == "goal_beside_wall") {
    scene = navigation::GoalBesideWallScene();
  } else if (n.field == "narrow_corridor") {
    scene = navigation::NarrowCorridorScene();
  } else {
    throw std::invalid_argument("NavigationSceneOf: unknown navigation.field '" + n.field + "'");
  }
  for (const scenario::NavigationObstacleSpec& o : n.obstacles) {
    scene.obstacles.push_back({o.center, o.radius_m});
  }
  for (const scenario::NavigationWallSpec& w : n.walls) {
    const std::vector<navigation::Circle> links =
        navigation::WallCircles(w.from, w.to, w.radius_m, n.safety_radius_m);
    scene.obstacles.insert(scene.obstacles.end(), links.begin(), links.end());
  }
  return scene;
}

navigation::NavigatorOptions NavigatorOptionsOf(const scenario::Scenario& scenario) {
  const scenario::NavigationSpec& n = scenario.navigation;
  navigation::NavigatorOptions o;
  o.setup.drive = DriveOf(n);
  o.setup.control_period_s = n.control_period_s;
  o.progress.stall_time_s = n.stall_time_s;
  o.subgoal.safety_radius_m = n.safety_radius_m;
  // One footprint for every method (the DWA keeps its margin as clearance beyond it).
  o.subgoal.robot_radius_m = n.footprint_radius_m;
  o.potential_field.robot_radius_m = n.footprint_radius_m;
  o.dwa.robot_radius_m = n.footprint_radius_m;
  return o;
}

navigation::KinematicSimulationOptions KinematicOptionsOf(const scenario::Scenario& scenario) {
  const scenario::NavigationSpec& n = scenario.navigation;
  navigation::KinematicSimulationOptions o;
  o.drive = DriveOf(n);
  o.control_period_s = n.control_period_s;
  o.footprint_radius_m = n.footprint_radius_m;
  o.criteria.time_limit_s = scenario.duration_s;
  return o;
}

}  // namespace trackbed::runner
