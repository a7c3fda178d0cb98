// The localization stack's options for a scenario's run: the scenario's
// `estimation` section (scenario::EstimationSpec) with the fields only the robot's
// given calibration knows filled in.
#pragma once

#include "trackbed/common/robot_calibration.h"
#include "trackbed/estimation/localization.h"
#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

/// The scenario's estimation.localization with the robot as the software knows it:
/// the wheels' sprocket radii and gauge, and the IMU's calibration, from `given`; the
/// ICR expansion χ from `given` when it has one, else the scenario's
/// estimation.icr_expansion; the encoders' resolution from robot.encoders; the gyro's
/// data-sheet noise (`gyro_model`) from robot.imu, its unset keys the realism profile's
/// part. Every other field is the scenario's.
estimation::LocalizationOptions LocalizationOptionsOf(const scenario::Scenario& scenario,
                                                      const calibration::RobotCalibration& given);

}  // namespace trackbed::runner
