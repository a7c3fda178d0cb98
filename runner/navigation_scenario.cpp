// The scenario's navigation section as the navigation library's inputs (see
// navigation_scenario.h).
#include "trackbed/runner/navigation_scenario.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "trackbed/common/units.h"

namespace trackbed::runner {
namespace {

using Field = scenario::NavigationSpec::Field;

// The generated scene of `field` (not kNone).
navigation::NavigationScene GeneratedScene(Field field, std::uint64_t seed) {
  switch (field) {
    case Field::kRandom:
      return navigation::RandomObstacleField(seed);
    case Field::kPaperLeft:
      return navigation::PaperSceneLeft();
    case Field::kPaperRight:
      return navigation::PaperSceneRight();
    case Field::kUTrap:
      return navigation::UTrapScene();
    case Field::kNarrowGap:
      return navigation::NarrowGapScene();
    case Field::kGoalBesideWall:
      return navigation::GoalBesideWallScene();
    case Field::kNarrowCorridor:
      return navigation::NarrowCorridorScene();
    case Field::kNone:
      break;
  }
  throw std::invalid_argument("GeneratedScene: no generated scene for navigation.field none");
}

}  // namespace

navigation::NavigationScene NavigationSceneOf(const scenario::Scenario& scenario) {
  const scenario::NavigationSpec& n = scenario.navigation;
  navigation::NavigationScene scene;
  if (n.field == Field::kNone) {
    scene.name = scenario.scene.name;
    const scenario::StartPose& s = scenario.robot.start;
    scene.start = {s.x_m, s.y_m, units::Radians(s.yaw_deg)};
    scene.goal = {n.goal.x_m, n.goal.y_m, units::Radians(n.goal.yaw_deg)};
  } else {
    scene = GeneratedScene(n.field, n.field_seed);
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
  navigation::NavigatorOptions o = n.navigator;
  o.subgoal.safety_radius_m = n.safety_radius_m;
  double footprint = n.footprint_radius_m;
  if (n.mode == scenario::NavigationSpec::Mode::kClosedLoop) {
    // The tracked robot as the navigators' "differential drive": sprocket radius, the
    // effective gauge χ·B (a skid-steer turns as if its tracks were that far apart), and
    // the wheel-speed limit of the top speed.
    const robot::TrackedVehicleOptions& v = scenario.robot.vehicle;
    o.setup.drive.wheel_radius_m = v.sprocket_radius_m;
    o.setup.drive.wheel_separation_m = scenario.estimation.icr_expansion * v.track_gauge_m;
    o.setup.drive.max_wheel_speed_radps = n.max_speed_mps / v.sprocket_radius_m;
    // The footprint the avoiders keep clear: the hull's half diagonal at least.
    footprint = std::max(footprint, 0.5 * v.hull_size_m.head<2>().norm());
  }
  // One footprint for every method (the DWA keeps its margin as clearance beyond it).
  o.subgoal.robot_radius_m = footprint;
  o.potential_field.robot_radius_m = footprint;
  o.dwa.robot_radius_m = footprint;
  return o;
}

navigation::KinematicSimulationOptions KinematicOptionsOf(const scenario::Scenario& scenario) {
  const scenario::NavigationSpec& n = scenario.navigation;
  navigation::KinematicSimulationOptions o = n.kinematic;
  o.drive = n.navigator.setup.drive;
  o.control_period_s = n.navigator.setup.control_period_s;
  o.footprint_radius_m = n.footprint_radius_m;
  o.criteria = navigation::SuccessCriteria{};
  o.criteria.time_limit_s = scenario.duration_s;
  return o;
}

navigation::ScanClusteringOptions ClusteringOptionsOf(const scenario::Scenario& scenario) {
  navigation::ScanClusteringOptions o = scenario.navigation.clustering;
  o.wall_spacing_m = std::min(o.wall_spacing_m, scenario.navigation.safety_radius_m);
  return o;
}

}  // namespace trackbed::runner
