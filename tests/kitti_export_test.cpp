// KITTI export round trip: what a run writes with outputs.save_images: kitti,
// read back by our KITTI reader, is exactly what the cameras saw.
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "trackbed/perception/kitti_sequence.h"
#include "trackbed/perception/opencv_views.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

TEST(KittiExportTest, ExportReadsBackAsTheSameImagesCalibrationAndPoses) {
  const scenario::Scenario s =
      scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/corridor.yaml",
                             {{"duration_s", "2"}, {"outputs.save_images", "kitti"}});
  const fs::path dir = fs::temp_directory_path() / "trackbed_kitti_export_test";
  fs::remove_all(dir);
  runner::RunToFolder(s, dir);

  // The same run again, in memory.
  std::vector<cv::Mat> lefts, rights;
  std::vector<Eigen::Isometry3d> T_world_left;
  std::vector<double> times;
  geometry::PinholeCamera K;
  runner::RunObservers obs;
  obs.on_stereo = [&](const runner::StereoFrame& f) {
    lefts.push_back(perception::AsCvMat(*f.left).clone());
    rights.push_back(perception::AsCvMat(*f.right).clone());
    T_world_left.push_back(f.T_world_left);
    times.push_back(f.t_s);
    K = f.rig->intrinsics();
  };
  runner::RunClosedLoop(s, obs);
  ASSERT_EQ(lefts.size(), 21u);  // 10 Hz over 2 s, both ends

  const perception::KittiSequence seq(dir / "images");
  ASSERT_EQ(seq.size(), lefts.size());
  EXPECT_NEAR(seq.calibration().left.fx, K.fx, 1e-9);
  EXPECT_NEAR(seq.calibration().left.cx, K.cx, 1e-9);
  EXPECT_NEAR(seq.calibration().left.cy, K.cy, 1e-9);
  EXPECT_NEAR(seq.calibration().baseline_m, 0.12, 1e-12);
  ASSERT_TRUE(seq.has_poses());
  for (std::size_t i = 0; i < seq.size(); ++i) {
    EXPECT_EQ(cv::norm(seq.LoadLeft(i), lefts[i], cv::NORM_INF), 0.0) << i;
    EXPECT_EQ(cv::norm(seq.LoadRight(i), rights[i], cv::NORM_INF), 0.0) << i;
    EXPECT_NEAR(seq.times_s()[i], times[i], 1e-6);
    const Eigen::Isometry3d expected = T_world_left[0].inverse() * T_world_left[i];
    EXPECT_LT((seq.poses()[i].matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-9) << i;
  }
  EXPECT_TRUE(fs::exists(dir / "stereo_calibration.json"));
}

}  // namespace
}  // namespace trackbed
