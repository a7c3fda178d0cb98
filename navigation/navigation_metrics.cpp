// Navigation metrics over a per-step log (see navigation_metrics.h).
#include "trackbed/navigation/navigation_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "trackbed/common/units.h"

namespace trackbed::navigation {

double PathLength(const std::vector<NavigationLogEntry>& log) {
  double length = 0.0;
  for (std::size_t k = 1; k < log.size(); ++k) {
    length += std::hypot(log[k].x_m - log[k - 1].x_m, log[k].y_m - log[k - 1].y_m);
  }
  return length;
}

int CountCollisions(const std::vector<NavigationLogEntry>& log) {
  int events = 0;
  bool in_contact = false;
  for (const NavigationLogEntry& row : log) {
    const bool contact = row.clearance_m < 0.0;
    if (contact && !in_contact) ++events;
    in_contact = contact;
  }
  return events;
}

double IntegratedAbsJerk(const std::vector<NavigationLogEntry>& log) {
  double total = 0.0;
  bool have_previous_accel = false;
  double previous_accel = 0.0;
  for (std::size_t k = 1; k < log.size(); ++k) {
    const double dt = log[k].t_s - log[k - 1].t_s;
    if (!(dt > 0.0)) continue;
    const double accel = (log[k].v_mps - log[k - 1].v_mps) / dt;
    if (have_previous_accel) total += std::abs(accel - previous_accel);  // |j_k|·dt
    previous_accel = accel;
    have_previous_accel = true;
  }
  return total;
}

NavigationMetrics ComputeNavigationMetrics(const std::vector<NavigationLogEntry>& log,
                                           const Pose2& goal, const SuccessCriteria& criteria,
                                           const std::string& status, int subgoals) {
  if (log.empty()) throw std::invalid_argument("ComputeNavigationMetrics: empty log");
  NavigationMetrics m;
  m.status = status;
  m.subgoals = subgoals;
  m.duration_s = log.back().t_s;
  m.path_length_m = PathLength(log);
  m.collisions = CountCollisions(log);
  m.integrated_abs_jerk = IntegratedAbsJerk(log);

  auto errors = [&](const NavigationLogEntry& row, double* position, double* heading) {
    *position = std::hypot(goal.x - row.x_m, goal.y - row.y_m);
    *heading = std::abs(geometry::WrapAngle(goal.yaw - row.yaw_rad));
  };
  double position = 0.0, heading = 0.0;
  errors(log.back(), &position, &heading);
  m.final_position_error_m = position;
  m.final_heading_error_deg = units::Degrees(heading);

  m.min_clearance_m = std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (const NavigationLogEntry& row : log) {
    m.min_clearance_m = std::min(m.min_clearance_m, row.clearance_m);
    sum += row.clearance_m;
  }
  m.mean_clearance_m = sum / static_cast<double>(log.size());

  m.success = position <= criteria.position_tolerance_m &&
              heading <= criteria.heading_tolerance_rad && m.collisions == 0 &&
              m.duration_s <= criteria.time_limit_s;
  if (m.success) {
    for (const NavigationLogEntry& row : log) {
      errors(row, &position, &heading);
      if (position <= criteria.position_tolerance_m && heading <= criteria.heading_tolerance_rad) {
        m.time_to_goal_s = row.t_s;
        break;
      }
    }
  }
  return m;
}

}  // namespace trackbed::navigation
