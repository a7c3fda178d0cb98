// KITTI export round trip: what a run writes with outputs.save_images: kitti,
// read back by our KITTI reader, is exactly what the cameras saw — rectified with the
// given calibration when that is not a rectified pair, as KITTI's images are.
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "trackbed/perception/kitti_sequence.h"
#include "trackbed/perception/opencv_views.h"
#include "trackbed/perception/stereo_rectifier.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

// Exports a 2 s corridor run under `realism` and checks that the export reads back as
// the images the cameras saw, rectified with the given calibration.
void CheckExport(const std::string& realism) {
  const scenario::Scenario s = scenario::LoadScenario(
      std::string(TRACKBED_SOURCE_DIR) + "/scenes/corridor.yaml",
      {{"duration_s", "2"}, {"outputs.save_images", "kitti"}, {"robot.realism", realism}});
  const fs::path dir = fs::temp_directory_path() / ("trackbed_kitti_export_test_" + realism);
  fs::remove_all(dir);
  runner::RunToFolder(s, dir);

  // The same run again, in memory.
  std::vector<cv::Mat> lefts, rights;
  std::vector<Eigen::Isometry3d> T_world_left;
  std::vector<double> times;
  const runner::RobotBuild robot = runner::BuildRunRobot(s);
  const perception::StereoRectifier rectifier(*robot.given.stereo);
  EXPECT_EQ(rectifier.identity(), realism == "ideal");
  // The rectified left camera in the raw one's frame: the rectifying rotation.
  const Eigen::Isometry3d T_left_rect =
      robot.given.stereo->T_body_left.inverse() * rectifier.T_body_left();
  runner::RunObservers obs;
  obs.on_stereo = [&](const runner::StereoFrame& f) {
    cv::Mat left, right;
    rectifier.Rectify(perception::AsCvMat(*f.left), perception::AsCvMat(*f.right), &left, &right);
    lefts.push_back(left.clone());
    rights.push_back(right.clone());
    T_world_left.push_back(rectifier.identity() ? f.T_world_left : f.T_world_left * T_left_rect);
    times.push_back(f.t_s);
  };
  runner::RunClosedLoop(s, obs);
  ASSERT_EQ(lefts.size(), 21u);  // 10 Hz over 2 s, both ends

  const perception::KittiSequence seq(dir / "images");
  ASSERT_EQ(seq.size(), lefts.size());
  const geometry::StereoCamera& K = rectifier.camera();
  EXPECT_NEAR(seq.calibration().left.fx, K.left.fx, 1e-9);
  EXPECT_NEAR(seq.calibration().left.cx, K.left.cx, 1e-9);
  EXPECT_NEAR(seq.calibration().left.cy, K.left.cy, 1e-9);
  EXPECT_NEAR(seq.calibration().baseline_m, K.baseline_m, 1e-12);
  if (realism == "ideal") {
    EXPECT_NEAR(seq.calibration().baseline_m, 0.12, 1e-12);
  }
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

TEST(KittiExportTest, ExportReadsBackAsTheSameImagesCalibrationAndPoses) { CheckExport("ideal"); }

TEST(KittiExportTest, AnUnrectifiedGivenPairIsExportedRectifiedWithItsProjections) {
  CheckExport("typical");
}

}  // namespace
}  // namespace trackbed
