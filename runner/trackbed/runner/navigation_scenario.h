// From a scenario's `navigation` section (Jung & Kim 2014; docs/navigation.md) to what the
// navigation library runs: the scene (start, goal, obstacle circles), the navigators'
// options, the kinematic simulation's and the scan clustering's. The section holds the
// library's options structs; these add what a run derives: the footprint and d_max every
// method shares and, in closed loop, the tracked robot as the navigators' drive.
#pragma once

#include <string>
#include <vector>

#include "trackbed/navigation/kinematic_simulation.h"
#include "trackbed/navigation/navigator_factory.h"
#include "trackbed/navigation/obstacle_fields.h"
#include "trackbed/navigation/scan_clustering.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

/// Start, goal and obstacles of the run: the generated field (if any) with the file's
/// obstacles and walls added; without a field, the start is `robot.start` and the goal
/// `navigation.goal`. Walls become chains of circles no farther apart than d_max.
navigation::NavigationScene NavigationSceneOf(const scenario::Scenario& scenario);

/// The navigators' options as a run of `scenario` builds them: `navigation`'s, with
/// d_max (`safety_radius_m`) and the footprint (`footprint_radius_m`) set in each
/// method. In closed loop the drive is the tracked robot (sprocket radius, effective
/// gauge χ·B, the wheel-speed limit of `max_speed_mps`) and the footprint at least the
/// hull's half diagonal.
navigation::NavigatorOptions NavigatorOptionsOf(const scenario::Scenario& scenario);

/// The kinematic simulation of `navigation.mode: kinematic`: `navigation.kinematic` with
/// the navigators' drive and control period, the footprint, and `duration_s` as the time
/// limit (the success tolerances stay fixed at 0.1 m and 2°).
navigation::KinematicSimulationOptions KinematicOptionsOf(const scenario::Scenario& scenario);

/// The scan clustering of `navigation.mode: closed_loop`: `navigation.clustering` with
/// its wall spacing at most d_max.
navigation::ScanClusteringOptions ClusteringOptionsOf(const scenario::Scenario& scenario);

}  // namespace trackbed::runner
