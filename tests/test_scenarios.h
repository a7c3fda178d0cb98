// Scenarios built in code for the physics tests: flat ground of one material,
// a scripted drive.
#pragma once

#include <string>

#include "trackbed/scenario/scenario.h"

namespace trackbed::testing {

/// Flat ground of `material`, the robot at the origin heading `yaw_deg`,
/// driving track speeds (left, right) [m/s] from t = 0; the run ends after
/// `drive_s` while the robot is still moving (so a stop's skid does not enter
/// the figures), or `stop_s` later with the tracks commanded to stop.
inline scenario::Scenario FlatTrackSpeedRun(const std::string& material, double left_mps,
                                            double right_mps, double drive_s, double yaw_deg = 0.0,
                                            double stop_s = 0.0) {
  scenario::Scenario s;
  s.seed = 7;
  s.duration_s = drive_s + stop_s;
  s.scene.name = "flat_" + material;
  s.scene.terrain.extent_m = {-15, -15, 15, 15};
  s.scene.terrain.cell_size_m = 0.5;
  s.scene.terrain.default_material = material;
  s.robot.start.yaw_deg = yaw_deg;
  s.drive.mode = scenario::DriveSpec::Mode::kScript;
  scenario::DriveCommand go;
  go.track_speeds = true;
  go.left_mps = left_mps;
  go.right_mps = right_mps;
  scenario::DriveCommand stop;
  stop.t_s = drive_s;
  stop.track_speeds = true;
  s.drive.script = {go, stop};
  return s;
}

}  // namespace trackbed::testing
