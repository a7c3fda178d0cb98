// What a navigation run leaves in its run folder besides the common logs:
// navigation.csv (one row per control step) and navigation.png, the path among the
// obstacles, their safety circles and the sub-goals (Jung & Kim 2014, figs. 5–8).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "trackbed/common/pose2.h"
#include "trackbed/navigation/circle_obstacle.h"
#include "trackbed/navigation/navigation_metrics.h"
#include "trackbed/navigation/subgoal_planner.h"
#include "trackbed/sim/static_object.h"

namespace trackbed::runner {

/// navigation.csv's header line.
constexpr char kNavigationCsvHeader[] =
    "t,x_m,y_m,yaw_rad,v_mps,yaw_rate_radps,left_radps,right_radps,target_x_m,target_y_m,"
    "subgoal_active,clearance_m";

/// One navigation.csv row (no line end).
std::string NavigationCsvRow(const navigation::NavigationLogEntry& e);

/// Draws navigation.png: the logged path, the obstacles grown by `safety_radius_m`,
/// start, goal and sub-goals.
void WriteNavigationMap(const std::filesystem::path& png, const std::string& title,
                        const std::vector<navigation::NavigationLogEntry>& log,
                        const std::vector<navigation::Circle>& obstacles, double safety_radius_m,
                        const geometry::Pose2& start, const geometry::Pose2& goal,
                        const std::vector<navigation::SubgoalRecord>& subgoals);

/// The scene's colliding objects as circles, for the map: cylinders as they are, boxes
/// as chains of circles along their longer side; meshes are left out.
std::vector<navigation::Circle> ObjectCircles(const std::vector<sim::StaticObject>& objects);

}  // namespace trackbed::runner
