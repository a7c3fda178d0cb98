// The KITTI twin (scenes/kitti_twin.yaml, docs/localization.md) at highway speed: its
// images exported in KITTI's layout carry a calibration-made scale bias into visual
// odometry, and estimating the rig's disparity offset removes it.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "trackbed/estimation/stereo_visual_odometry.h"
#include "trackbed/estimation/trajectory_metrics.h"
#include "trackbed/perception/kitti_sequence.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

// The median ratio of VO's to the true length of each frame's motion over `sequence`.
double MedianFrameLengthRatio(const perception::KittiSequence& sequence, bool estimate_offset) {
  estimation::StereoVisualOdometryOptions options;
  options.estimate_disparity_offset = estimate_offset;
  estimation::StereoVisualOdometry vo(sequence.calibration(), options);
  estimation::Trajectory est, gt;
  for (std::size_t k = 0; k < sequence.size(); ++k) {
    const double t = sequence.times_s()[k];
    est.push_back({t, vo.Process(sequence.LoadLeft(k), sequence.LoadRight(k), t).T_world_cam});
    gt.push_back({t, sequence.poses()[k]});
  }
  return estimation::FrameToFrameError(gt, est).length_ratio.median;
}

TEST(KittiTwinTest, AtHighwaySpeedTheCalibrationsDisparityOffsetIsFoundAndTheScaleBiasGoes) {
  // 100 m at 25 m/s (40 frames) through seed 1's camera as built and calibrated under
  // `typical`: the given calibration's principal points and relative rotation offset the
  // rectified disparities by a fraction of a pixel.
  const scenario::Scenario s =
      scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/kitti_twin.yaml",
                             {{"duration_s", "4"},
                              {"drive.speed_mps", "25"},
                              {"robot.realism", "typical"},
                              {"estimation.enabled", "false"},
                              {"outputs.mcap", "false"}});
  const fs::path dir = fs::temp_directory_path() / "trackbed_kitti_twin_test";
  fs::remove_all(dir);
  runner::ClosedLoopOptions options;
  options.dir = dir;
  runner::ClosedLoop(s, std::move(options)).Run();
  const perception::KittiSequence sequence(dir / "images");
  ASSERT_EQ(sequence.size(), 41u);
  // Under `ideal` the twin's per-frame median stays within 0.2 % of 1 at 5, 15 and
  // 25 m/s, and under `typical` with the camera's calibration given true within 0.02 %
  // (docs/results/2026-12-05-kitti-twin.md): a median off by more than 1 % is the
  // calibration's offset. As measured, VO reads the frames 4.3 % short (0.9572); with
  // the offset estimated, 0.1 % (0.9988).
  const double measured = MedianFrameLengthRatio(sequence, false);
  const double corrected = MedianFrameLengthRatio(sequence, true);
  std::printf("per-frame median length ratio: as measured %.4f, with the offset %.4f\n", measured,
              corrected);
  EXPECT_LT(measured, 0.99);
  EXPECT_NEAR(corrected, 1.0, 0.01);
}

}  // namespace
}  // namespace trackbed
