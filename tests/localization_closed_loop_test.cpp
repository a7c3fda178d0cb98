// The localization stack in closed loop on short routes of the shipped scenes:
// the orderings of Ham et al. 2012 that hold today, on ground-truth error.
#include <gtest/gtest.h>

#include "trackbed/scenes/closed_loop_runner.h"
#include "trackbed/scenes/scenario_yaml.h"

namespace trackbed {
namespace {

scenes::RunMetrics RunScene(const std::string& scene, double seconds) {
  return scenes::RunClosedLoop(
      scenes::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/" + scene,
                           {{"duration_s", std::to_string(seconds)}, {"seed", "3"}}));
}

double Ate(const scenes::RunMetrics& m, const char* name) {
  return m.estimators.at(name).ate_rmse_m;
}

TEST(LocalizationClosedLoopTest, InThePlainCorridorWheelOdometryBeatsVision) {
  const scenes::RunMetrics m = RunScene("corridor.yaml", 30.0);
  ASSERT_TRUE(m.completed) << m.stop_reason;
  // Few corners: most VO frames fail, so VO loses most of the motion.
  EXPECT_GT(m.localization.vo_failures, m.localization.vo_frames / 2);
  EXPECT_LT(Ate(m, "wheel_odometry"), 0.05);
  EXPECT_LT(10.0 * Ate(m, "wheel_odometry"), Ate(m, "visual_odometry"));
  // Fusion leans on the wheels there and stays close to the truth.
  EXPECT_LT(Ate(m, "fused"), 0.1);
}

TEST(LocalizationClosedLoopTest, OnRoughTexturedGroundVisionBeatsWheelOdometryAndFusionHelps) {
  const scenes::RunMetrics m = RunScene("outdoor.yaml", 20.0);
  ASSERT_TRUE(m.completed) << m.stop_reason;
  EXPECT_LT(m.localization.vo_failures, 3);
  EXPECT_GT(m.localization.mean_inliers, 100.0);
  EXPECT_LT(Ate(m, "visual_odometry"), Ate(m, "wheel_odometry"));
  EXPECT_LT(Ate(m, "fused"), Ate(m, "wheel_odometry"));
  // Slip is real here: the slip-aware odometry beats the no-slip baseline.
  EXPECT_LT(Ate(m, "wheel_odometry"), Ate(m, "wheel_odometry_noslip"));
  // The EKF reads the same encoders with no slip model, but weighs them against the
  // gyro and VO.
  EXPECT_LT(Ate(m, "ekf"), Ate(m, "wheel_odometry"));
  EXPECT_LT(10.0 * Ate(m, "ekf"), Ate(m, "wheel_odometry_noslip"));
}

}  // namespace
}  // namespace trackbed
