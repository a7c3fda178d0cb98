// The localization stack's options for a run (see localization_options.h).
#include "trackbed/runner/localization_options.h"

namespace trackbed::runner {

estimation::LocalizationOptions LocalizationOptionsOf(const scenario::Scenario& scenario,
                                                      const calibration::RobotCalibration& given) {
  estimation::LocalizationOptions lo = scenario.estimation.localization;
  lo.wheel.sprocket_radius_m = given.vehicle.sprocket_radius_left_m;
  lo.wheel.right_sprocket_radius_m = given.vehicle.sprocket_radius_right_m;
  lo.wheel.track_gauge_m = given.vehicle.track_gauge_m;
  lo.wheel.icr_expansion = given.vehicle.icr_expansion.value_or(scenario.estimation.icr_expansion);
  lo.wheel.ticks_per_rev = scenario.robot.encoders.ticks_per_rev;
  lo.imu = given.imu;
  return lo;
}

}  // namespace trackbed::runner
