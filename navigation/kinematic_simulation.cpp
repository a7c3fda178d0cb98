// The kinematic differential-drive simulation (see kinematic_simulation.h).
#include "trackbed/navigation/kinematic_simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {

void KinematicSimulationOptions::Validate() const {
  option_check::Nested("drive", drive);
  option_check::Positive("control_period_s", control_period_s);
  option_check::Positive("criteria.position_tolerance_m", criteria.position_tolerance_m);
  option_check::InRange("criteria.heading_tolerance_rad", criteria.heading_tolerance_rad, 1e-9,
                        M_PI);
  option_check::Positive("criteria.time_limit_s", criteria.time_limit_s);
  option_check::NonNegative("footprint_radius_m", footprint_radius_m);
  if (substeps < 1) throw OptionError("substeps", "must be >= 1");
}

KinematicRun RunKinematicSimulation(const NavigationScene& scene, Navigator& navigator,
                                    const KinematicSimulationOptions& options) {
  options.Validate();
  const Pose2& g = navigator.goal();
  if (g.x != scene.goal.x || g.y != scene.goal.y || g.yaw != scene.goal.yaw) {
    throw std::invalid_argument("RunKinematicSimulation: the navigator's goal is not scene '" +
                                scene.name + "''s goal");
  }
  const double dt = options.control_period_s;
  const long steps = std::lround(options.criteria.time_limit_s / dt);
  KinematicRun run;
  Pose2 pose = scene.start;
  double clearance =
      FootprintClearance({pose.x, pose.y}, options.footprint_radius_m, scene.obstacles);
  std::string status = "time_limit";
  const auto log_row = [&run, &options](const NavigationLogEntry& row) {
    run.log.push_back(row);
    if (options.on_row) options.on_row(row);
  };
  for (long k = 0;; ++k) {
    NavigationLogEntry row;
    row.t_s = static_cast<double>(k) * dt;
    row.x_m = pose.x;
    row.y_m = pose.y;
    row.yaw_rad = pose.yaw;
    row.clearance_m = clearance;
    row.target_x_m = scene.goal.x;
    row.target_y_m = scene.goal.y;
    if (clearance < 0.0 && options.stop_on_collision) {
      status = "collision";
      log_row(row);
      break;
    }
    if (k >= steps) {
      log_row(row);
      break;
    }
    const NavigationCommand command = navigator.Update(pose, scene.obstacles);
    row.v_mps = command.twist.v_mps;
    row.yaw_rate_radps = command.twist.yaw_rate_radps;
    row.left_radps = command.wheels.left_radps;
    row.right_radps = command.wheels.right_radps;
    row.target_x_m = command.target.x();
    row.target_y_m = command.target.y();
    row.subgoal_active = command.subgoal_active;
    log_row(row);
    if (command.status != NavigationStatus::kDriving) {
      status = NavigationStatusName(command.status);
      break;
    }
    // The robot obeys the wheel-speed limit whatever the navigator asks.
    const WheelSpeeds wheels =
        SaturateProportionally(command.wheels, options.drive.max_wheel_speed_radps);
    const double h = dt / options.substeps;
    clearance = std::numeric_limits<double>::infinity();
    for (int s = 0; s < options.substeps; ++s) {
      pose =
          IntegrateWheelAngles(options.drive, pose, wheels.left_radps * h, wheels.right_radps * h);
      clearance = std::min(
          clearance,
          FootprintClearance({pose.x, pose.y}, options.footprint_radius_m, scene.obstacles));
    }
  }
  run.subgoals = navigator.subgoals();
  run.metrics = ComputeNavigationMetrics(run.log, scene.goal, options.criteria, status,
                                         static_cast<int>(run.subgoals.size()));
  return run;
}

}  // namespace trackbed::navigation
