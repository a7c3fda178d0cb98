// The robot of one run (see robot_build.h).
#include "trackbed/runner/robot_build.h"

#include "trackbed/common/split_mix.h"
#include "trackbed/robot/as_built.h"

namespace trackbed::runner {

RobotBuild BuildRobot(const scenario::Scenario& scenario, const WheelCalibrator& calibrate_wheels) {
  const scenario::RobotSpec& rs = scenario.robot;
  const robot::Imperfections imperfections = rs.imperfections.Resolve(rs.realism);
  const std::uint64_t seed = rs.AsBuiltSeed(scenario.seed);
  RobotBuild b;
  b.design =
      robot::DesignCalibration(rs.vehicle, robot::WithCameraEffectsResolved(rs.stereo, rs.realism));
  b.truth = robot::DrawAsBuilt(b.design, imperfections, split_mix::Stream(seed, 0));
  if (!rs.calibration_dir.empty()) {
    b.given = calibration::ReadCalibrationFolder(rs.calibration_dir, rs.stereo.enabled);
  } else {
    b.given =
        robot::DrawGivenCalibration(b.truth, b.design, imperfections, split_mix::Stream(seed, 1));
    b.given.stereo_source = b.given.stereo == b.truth.stereo
                                ? "the cameras as built (no calibration error)"
                                : "the cameras as built with calibration errors drawn "
                                  "from published parameter standard deviations";
    b.given.imu_source = "the IMU's design: a perfect IMU aligned with the body";
    if (*imperfections.wheel_calibration == robot::WheelCalibration::kStraightRun &&
        scenario.estimation.enabled) {
      b.given.vehicle = calibrate_wheels(scenario);
      b.given.vehicle_source =
          "the straight calibration run (scenes/calibration/straight_line.yaml) on the robot as "
          "built";
    } else {
      b.given.vehicle = b.truth.vehicle;
      b.given.vehicle_source = "the vehicle as built (no calibration error)";
    }
  }
  if (!b.given.vehicle.icr_expansion)
    b.given.vehicle.icr_expansion = scenario.estimation.icr_expansion;
  return b;
}

}  // namespace trackbed::runner
