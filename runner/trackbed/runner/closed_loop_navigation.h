// Point-to-point navigation on the simulated tracked robot (docs/navigation.md, `closed_loop`
// mode): at each control period the navigator sees the robot's estimated pose and the
// obstacle circles clustered from the latest range scan, and its body twist becomes
// track speeds through the effective gauge χ·B. Ground truth is logged beside it for
// the metrics (path, clearance of the chassis box against the real objects).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/common/skid_steer.h"
#include "trackbed/navigation/navigation_metrics.h"
#include "trackbed/navigation/navigator.h"
#include "trackbed/navigation/navigator_factory.h"
#include "trackbed/navigation/scan_clustering.h"
#include "trackbed/robot/range_sensor.h"
#include "trackbed/runner/commander.h"
#include "trackbed/scenario/scenario.h"
#include "trackbed/sim/triangle_mesh.h"

namespace trackbed::runner {

/// The navigator as the run's commander, at `navigation.control_period_s`.
class ClosedLoopNavigation : public Commander {
 public:
  /// `objects` and `meshes` are the world's (sim::World::objects, mesh_solids: for the
  /// chassis clearance logged with ground truth); `on_step` (may be empty) sees every
  /// control step's log entry.
  using StepObserver = std::function<void(const navigation::NavigationLogEntry&)>;
  ClosedLoopNavigation(const scenario::Scenario& scenario, std::vector<sim::StaticObject> objects,
                       std::vector<std::shared_ptr<const sim::PlacedMesh>> meshes,
                       StepObserver on_step);

  double period_s() const override { return period_s_; }
  bool needs_estimates() const override { return true; }
  /// Keeps the latest scan for the next control step.
  void AddScan(const robot::RangeScanSample& scan) override { scan_ = scan; }
  /// One control step from the pose `navigation.pose_source` names; ends the run with
  /// "navigation <status>" once the navigator stops.
  ControlOutput Update(const ControlInput& input) override;
  /// metrics.json `navigation` and the sub-goals for the map plot.
  void AddMetrics(bool time_ran_out, RunMetrics* metrics) const override;

  /// One control step at `t_s`: `pose` is what the robot believes, `T_world_body` the
  /// truth (logged, never shown to the navigator). Returns the track speeds to command.
  kinematics::TrackSpeeds Command(double t_s, const geometry::Pose2& pose,
                                  const Eigen::Isometry3d& T_world_body);
  /// The navigator has ended the run (reached, goal in obstacle, stalled).
  bool finished() const { return status_ != navigation::NavigationStatus::kDriving; }
  const navigation::NavigationLogEntry& last_entry() const { return log_.back(); }
  /// Metrics over the logged ground truth; `time_limit` when the run ran out of time.
  navigation::NavigationMetrics Metrics(bool time_limit) const;
  std::vector<navigation::SubgoalRecord> subgoals() const { return navigator_->subgoals(); }
  const std::vector<navigation::Circle>& last_obstacles() const { return obstacles_; }

 private:
  navigation::NavigationMethod method_;
  scenario::NavigationSpec::PoseSource pose_source_;
  std::vector<sim::StaticObject> objects_;
  std::vector<std::shared_ptr<const sim::PlacedMesh>> meshes_;
  Eigen::Vector2d hull_z_range_m_;  // the chassis's heights about its body origin
  StepObserver on_step_;
  std::unique_ptr<navigation::Navigator> navigator_;
  navigation::Pose2 goal_;
  double period_s_;
  double time_limit_s_;  // the run's, the standstill included
  double standstill_s_;  // drive.start_standstill_s: the navigator starts after it
  double gauge_eff_m_;
  double max_yaw_rate_radps_;
  Eigen::Vector2d mount_xy_m_;
  Eigen::Vector2d hull_xy_m_;
  navigation::ScanClusteringOptions clustering_;
  std::optional<robot::RangeScanSample> scan_;
  std::vector<navigation::Circle> obstacles_;
  std::vector<navigation::NavigationLogEntry> log_;
  // The believed pose at the last control step: the measured twist's start.
  std::optional<std::pair<double, geometry::Pose2>> last_pose_;
  navigation::NavigationStatus status_ = navigation::NavigationStatus::kDriving;
};

}  // namespace trackbed::runner
