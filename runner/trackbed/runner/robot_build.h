// The robot of one run: its design, the robot as built that the plant simulates, and
// the calibration its software is given (docs/calibration.md).
#pragma once

#include <functional>

#include "trackbed/common/robot_calibration.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

struct RobotBuild {
  calibration::RobotCalibration design;
  calibration::RobotCalibration truth;  ///< the robot as built: the plant's
  calibration::RobotCalibration given;  ///< what the software is given
};

/// Runs the straight calibration run for a scenario's robot and returns its fit
/// (wheel_calibration_run.h); given by the closed loop, which can run it.
using WheelCalibrator =
    std::function<calibration::VehicleCalibration(const scenario::Scenario& scenario)>;

/// Draws `scenario`'s robot as built (robot.realism, robot.imperfections,
/// robot.as_built_seed) and its given calibration: the files of robot.calibration_dir
/// when set; else the camera's drawn calibration errors, the IMU as the software assumes
/// it, and the vehicle's radii from `calibrate_wheels` (when the imperfections ask for
/// the straight run and estimation is on) or the truth. χ comes from the calibration
/// folder's file when it has one, else estimation.icr_expansion.
RobotBuild BuildRobot(const scenario::Scenario& scenario, const WheelCalibrator& calibrate_wheels);

}  // namespace trackbed::runner
