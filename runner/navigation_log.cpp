// Navigation's run-folder files (see navigation_log.h).
#include "trackbed/runner/navigation_log.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "trackbed/plot/plots.h"

namespace trackbed::runner {

std::string NavigationCsvRow(const navigation::NavigationLogEntry& e) {
  char line[512];
  std::snprintf(line, sizeof(line), "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%.9g",
                e.t_s, e.x_m, e.y_m, e.yaw_rad, e.v_mps, e.yaw_rate_radps, e.left_radps,
                e.right_radps, e.target_x_m, e.target_y_m, e.subgoal_active ? 1 : 0, e.clearance_m);
  return line;
}

// The path among the obstacles, their safety circles and the sub-goals (Jung & Kim
// 2014, figs. 5–8).
void WriteNavigationMap(const std::filesystem::path& png, const std::string& title,
                        const std::vector<navigation::NavigationLogEntry>& log,
                        const std::vector<navigation::Circle>& obstacles, double safety_radius_m,
                        const geometry::Pose2& start, const geometry::Pose2& goal,
                        const std::vector<navigation::SubgoalRecord>& subgoals) {
  std::vector<plot::PlotCircle> circles;
  for (const navigation::Circle& c : obstacles) {
    circles.push_back({c.centre, c.radius_m + safety_radius_m, false});
  }
  for (const navigation::Circle& c : obstacles) circles.push_back({c.centre, c.radius_m});
  std::vector<plot::PlotMarker> markers = {{{start.x, start.y}, "start"},
                                           {{goal.x, goal.y}, "goal"}};
  for (std::size_t k = 0; k < subgoals.size(); ++k) {
    markers.push_back({subgoals[k].position, "sub-goal " + std::to_string(k + 1)});
  }
  plot::PlotSeries path{"path (ground truth)", {}};
  for (const navigation::NavigationLogEntry& e : log) path.points.emplace_back(e.x_m, e.y_m);
  plot::WriteMapPlot(png, title, {path}, circles, markers);
}

// The scene's colliding objects as circles, for the map: cylinders as they are, boxes
// as chains of circles along their longer side; meshes are not drawn.
std::vector<navigation::Circle> ObjectCircles(const std::vector<sim::StaticObject>& objects) {
  std::vector<navigation::Circle> circles;
  for (const sim::StaticObject& o : objects) {
    if (!o.collides || o.shape == sim::StaticObject::Shape::kMesh) continue;
    if (o.shape == sim::StaticObject::Shape::kCylinder) {
      circles.push_back({o.center_m, o.radius_m});
      continue;
    }
    const bool along_x = o.size_m.x() >= o.size_m.y();
    const double half_long = 0.5 * (along_x ? o.size_m.x() : o.size_m.y());
    const double radius = 0.5 * (along_x ? o.size_m.y() : o.size_m.x());
    const double axis_yaw = o.yaw_rad + (along_x ? 0.0 : M_PI / 2);
    const Eigen::Vector2d u(std::cos(axis_yaw), std::sin(axis_yaw));
    const double reach = std::max(half_long - radius, 0.0);
    const std::vector<navigation::Circle> chain = navigation::WallCircles(
        o.center_m - reach * u, o.center_m + reach * u, radius, std::max(radius, 0.05));
    circles.insert(circles.end(), chain.begin(), chain.end());
  }
  return circles;
}

}  // namespace trackbed::runner
