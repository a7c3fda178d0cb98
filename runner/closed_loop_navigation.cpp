// Closed-loop navigation on the tracked robot (see closed_loop_navigation.h).
#include "trackbed/runner/closed_loop_navigation.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "trackbed/common/units.h"
#include "trackbed/navigation/navigator_factory.h"
#include "trackbed/runner/footprint_clearance.h"
#include "trackbed/runner/navigation_scenario.h"
#include "trackbed/runner/run_metrics.h"

namespace trackbed::runner {
ClosedLoopNavigation::ClosedLoopNavigation(
    const scenario::Scenario& s, std::vector<sim::StaticObject> objects,
    std::vector<std::shared_ptr<const sim::PlacedMesh>> meshes, StepObserver on_step)
    : method_(s.navigation.method),
      pose_source_(s.navigation.pose_source),
      objects_(std::move(objects)),
      meshes_(std::move(meshes)),
      // From the ground at rest (the centre of mass is com_height_m above it) to
      // the hull's top.
      hull_z_range_m_(-s.robot.vehicle.com_height_m, s.robot.vehicle.ground_clearance_m +
                                                         s.robot.vehicle.hull_size_m.z() -
                                                         s.robot.vehicle.com_height_m),
      on_step_(std::move(on_step)),
      goal_{s.navigation.goal.x_m, s.navigation.goal.y_m,
            units::Radians(s.navigation.goal.yaw_deg)},
      period_s_(s.navigation.navigator.setup.control_period_s),
      time_limit_s_(s.RunDuration(scenario::DriveSource::kScenario)),
      standstill_s_(s.drive.start_standstill_s),
      gauge_eff_m_(s.estimation.icr_expansion * s.robot.vehicle.track_gauge_m),
      max_yaw_rate_radps_(s.navigation.max_yaw_rate_radps),
      mount_xy_m_(s.robot.range_sensor.mount_m.head<2>()),
      hull_xy_m_(s.robot.vehicle.hull_size_m.head<2>()),
      clustering_(ClusteringOptionsOf(s)) {
  navigator_ = navigation::MakeNavigator(s.navigation.method, NavigatorOptionsOf(s), goal_);
}

ControlOutput ClosedLoopNavigation::Update(const ControlInput& input) {
  using PoseSource = scenario::NavigationSpec::PoseSource;
  const auto believed = [&] {
    if (pose_source_ == PoseSource::kGroundTruth) return geometry::PlanarPose(input.T_world_body);
    // The scenario's validation makes estimation on for the other pose sources.
    if (!input.estimates) {
      throw std::logic_error(std::string("navigation: ") +
                             scenario::NavigationSpec::ToString(pose_source_) + " has no estimate");
    }
    return geometry::PlanarPose(pose_source_ == PoseSource::kFused
                                    ? input.estimates->fused()
                                    : input.estimates->wheel_odometry());
  };
  ControlOutput out;
  // The start standstill (drive.start_standstill_s): the tracks held at zero, so the
  // stack takes the gyro's bias; the navigator and its log start after it.
  if (input.t_s < standstill_s_ - 1e-9) return out;
  out.tracks = Command(input.t_s, believed(), input.T_world_body);
  if (on_step_) on_step_(log_.back());
  if (finished()) out.stop_reason = "navigation " + Metrics(false).status;
  return out;
}

void ClosedLoopNavigation::AddMetrics(bool time_ran_out, RunMetrics* metrics) const {
  metrics->navigation_method = navigation::ToString(method_);
  metrics->navigation = Metrics(time_ran_out);
  metrics->navigation_subgoals = subgoals();
}

kinematics::TrackSpeeds ClosedLoopNavigation::Command(double t_s, const geometry::Pose2& pose,
                                                      const Eigen::Isometry3d& T_world_body) {
  obstacles_.clear();
  if (scan_) {
    // The scan is placed where the robot believes its sensor is.
    const geometry::Pose2 sensor = geometry::Compose(pose, {mount_xy_m_.x(), mount_xy_m_.y(), 0.0});
    navigation::RangeScan scan{scan_->ranges_m, scan_->angles_rad, scan_->max_range_m};
    obstacles_ = navigation::ClusterScan(scan, sensor, clustering_);
  }
  if (last_pose_ && t_s > last_pose_->first) {
    // The twist the believed pose moved by over the last period: the robot's as measured,
    // which the skid, the yaw-rate limit below and the tracks' dynamics set apart from
    // the last command.
    const double dt = t_s - last_pose_->first;
    const geometry::Pose2 step = geometry::Between(last_pose_->second, pose);
    navigator_->SetMeasuredTwist({step.x / dt, step.yaw / dt});
  }
  last_pose_ = std::make_pair(t_s, pose);
  const navigation::NavigationCommand c = navigator_->Update(pose, obstacles_);
  status_ = c.status;
  const geometry::Pose2 truth = geometry::PlanarPose(T_world_body);
  navigation::NavigationLogEntry e;
  e.t_s = t_s;
  e.x_m = truth.x;
  e.y_m = truth.y;
  e.yaw_rad = truth.yaw;
  e.v_mps = c.twist.v_mps;
  e.yaw_rate_radps = c.twist.yaw_rate_radps;
  e.left_radps = c.wheels.left_radps;
  e.right_radps = c.wheels.right_radps;
  e.target_x_m = c.target.x();
  e.target_y_m = c.target.y();
  e.subgoal_active = c.subgoal_active;
  e.clearance_m = ChassisClearance(T_world_body, hull_xy_m_, objects_, meshes_, hull_z_range_m_);
  log_.push_back(e);
  kinematics::BodyTwist twist{c.twist.v_mps, c.twist.yaw_rate_radps};
  if (std::abs(twist.yaw_rate_radps) > max_yaw_rate_radps_) {
    const double scale = max_yaw_rate_radps_ / std::abs(twist.yaw_rate_radps);
    twist.v_mps *= scale;
    twist.yaw_rate_radps *= scale;
  }
  e.v_mps = twist.v_mps;
  e.yaw_rate_radps = twist.yaw_rate_radps;
  log_.back() = e;
  return kinematics::TrackSpeedsFromTwist(twist, gauge_eff_m_);
}

navigation::NavigationMetrics ClosedLoopNavigation::Metrics(bool time_limit) const {
  navigation::SuccessCriteria criteria;  // docs/navigation.md: 0.1 m and 2° by ground truth
  criteria.time_limit_s = time_limit_s_;
  const std::string status =
      time_limit ? std::string("time_limit") : navigation::NavigationStatusName(status_);
  return navigation::ComputeNavigationMetrics(log_, goal_, criteria, status,
                                              static_cast<int>(navigator_->subgoals().size()));
}

}  // namespace trackbed::runner
