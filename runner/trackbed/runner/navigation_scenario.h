// From a scenario's `navigation` section (Jung & Kim 2014; docs/navigation.md) to what the
// navigation library runs: the scene (start, goal, obstacle circles), the
// navigators' options and the kinematic simulation's options.
#pragma once

#include <string>
#include <vector>

#include "trackbed/navigation/kinematic_simulation.h"
#include "trackbed/navigation/navigator_factory.h"
#include "trackbed/navigation/obstacle_fields.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

/// Start, goal and obstacles of the run: the generated field (if any) with the file's
/// obstacles and walls added; without a field, the start is `robot.start` and the goal
/// `navigation.goal`. Walls become chains of circles no farther apart than d_max.
navigation::NavigationScene NavigationSceneOf(const scenario::Scenario& scenario);

/// The options every navigation method gets from the scenario (robot, control period,
/// d_max, stall time); the methods' gains keep their tuned defaults.
navigation::NavigatorOptions NavigatorOptionsOf(const scenario::Scenario& scenario);

/// The kinematic simulation of `navigation.mode: kinematic`; the time limit is
/// `duration_s`.
navigation::KinematicSimulationOptions KinematicOptionsOf(const scenario::Scenario& scenario);

}  // namespace trackbed::runner
