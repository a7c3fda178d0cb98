// The straight calibration run (see wheel_calibration_run.h).
#include "trackbed/runner/wheel_calibration_run.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "trackbed/common/pose2.h"
#include "trackbed/robot/encoder.h"

namespace trackbed::runner {
scenario::Scenario StraightRunScenario(const scenario::Scenario& s) {
  scenario::Scenario c;  // scenes/calibration/straight_line.yaml, key for key
  c.seed = 1;
  c.duration_s = 25.0;
  c.scene.name = "straight_line";
  c.scene.terrain.extent_m = Eigen::Vector4d(-5, -5, 15, 5);
  c.scene.terrain.cell_size_m = 0.5;
  c.scene.terrain.default_material = "hard_floor";
  c.robot = s.robot;
  c.robot.start = scenario::StartPose{};
  c.robot.stereo.enabled = false;
  c.robot.range_sensor.enabled = false;
  c.robot.as_built_seed = s.robot.AsBuiltSeed(s.seed);
  c.robot.calibration_dir.clear();
  // The robot under calibration has no calibration yet: nothing in this run uses one.
  c.robot.imperfections = s.robot.imperfections.Resolve(s.robot.realism);
  c.robot.imperfections.wheel_calibration = robot::WheelCalibration::kTruth;
  c.estimation.enabled = false;
  c.drive.mode = scenario::DriveSpec::Mode::kScript;
  scenario::DriveCommand go;
  go.track_speeds = true;
  go.left_mps = go.right_mps = 0.4;
  c.drive.script = {go};
  return c;
}

StraightRunFit::StraightRunFit(int ticks_per_rev, double track_gauge_m, double icr_expansion)
    : ticks_per_rev_(ticks_per_rev), gauge_m_(track_gauge_m), chi_(icr_expansion) {}

void StraightRunFit::Add(const RunSample& sample) {
  if (!has_first_) {
    first_ = sample;
    has_first_ = true;
  }
  last_ = sample;
}

calibration::VehicleCalibration StraightRunFit::Result() const {
  const Eigen::Vector3d d =
      last_.chassis.T_world_body.translation() - first_.chassis.T_world_body.translation();
  const double chord = d.head<2>().norm();
  if (!has_first_ || !(chord >= 1.0)) {
    throw std::runtime_error("straight calibration run: the robot drove " + std::to_string(chord) +
                             " m, less than the 1 m a fit needs");
  }
  double dyaw = geometry::PlanarPose(last_.chassis.T_world_body).yaw -
                geometry::PlanarPose(first_.chassis.T_world_body).yaw;
  dyaw = std::remainder(dyaw, 2.0 * M_PI);
  const double half = 0.5 * dyaw;
  const double path = std::abs(half) < 1e-9 ? chord : chord * half / std::sin(half);
  const double theta_l = robot::TicksToAngle(last_.ticks[0] - first_.ticks[0], ticks_per_rev_);
  const double theta_r = robot::TicksToAngle(last_.ticks[1] - first_.ticks[1], ticks_per_rev_);
  // r_l θ_l + r_r θ_r = 2s (the distance), r_r θ_r − r_l θ_l = Δψ·B_eff (the turn).
  const double turn = dyaw * chi_ * gauge_m_;
  calibration::VehicleCalibration c;
  c.sprocket_radius_left_m = (2.0 * path - turn) / (2.0 * theta_l);
  c.sprocket_radius_right_m = (2.0 * path + turn) / (2.0 * theta_r);
  c.track_gauge_m = gauge_m_;
  c.icr_expansion = chi_;
  return c;
}

}  // namespace trackbed::runner
