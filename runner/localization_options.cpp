// The localization stack's options for a run (see localization_options.h).
#include "trackbed/runner/localization_options.h"

#include <cmath>

#include "trackbed/robot/as_built.h"
#include "trackbed/robot/imu_parts.h"

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
  // The gyro's data sheet: the robot.imu keys, else the realism profile's part.
  const robot::ImuOptions imu =
      robot::WithImuPartResolved(scenario.robot.imu, scenario.robot.realism);
  lo.gyro_model.noise_density = *imu.gyro_noise_density;
  lo.gyro_model.bias_random_walk = *imu.gyro_bias_random_walk;
  lo.gyro_model.turn_on_bias_std = *imu.gyro_initial_bias_std;
  double markov_var = 0.0;
  for (const double s : *imu.gyro_bias_markov_std) markov_var += s * s;
  lo.gyro_model.bias_instability_std = std::sqrt(markov_var);
  // The disparity offset's spread the stereo calibration states: the two principal
  // points' columns independently, and the pair's relative yaw (about the left camera's
  // y axis) through fx.
  if (given.stereo) {
    const robot::Imperfections imp = scenario.robot.imperfections.Resolve(scenario.robot.realism);
    const double pp = *imp.principal_point_calibration_std_px;
    const double yaw = given.stereo->left.fx * imp.stereo_rotation_calibration_std_mrad->y() * 1e-3;
    lo.vo.calibration_disparity_offset_std_px = std::sqrt(2.0 * pp * pp + yaw * yaw);
  }
  return lo;
}

}  // namespace trackbed::runner
