// People crossing the view during a repeat (scenes/tr_occlusion.yaml, Choi &
// Ha 2011 experiment 1), on the first 3.5 m of the room with three crossings while the
// robot stands: each crossing is a place where features are lost; the 3D repeat
// recovers most of them from their stored patches once the person has passed and
// finishes the route; the 2D repeat recovers none.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {

using namespace scenario;  // the scenarios these tests run
namespace {

namespace fs = std::filesystem;

TeachRepeatMetrics RunShortRoom(const std::string& method) {
  const fs::path dir = fs::path(testing::TempDir()) / ("trackbed_tr_occlusion_" + method);
  fs::remove_all(dir);
  const Scenario s = LoadScenario(
      std::string(TRACKBED_SOURCE_DIR) + "/scenes/tr_occlusion.yaml",
      {{"drive.waypoints", "[[0, 0], [3.5, 0]]"},
       {"teach_repeat.method", method},
       {"teach_repeat.occluders",
        "[{waypoints: [[1.8, -3], [1.8, 3]], speed_mps: 1.0, start_s: 6, back_and_forth: false},"
        " {waypoints: [[2.35, -3], [2.35, 3]], speed_mps: 1.0, start_s: 26, back_and_forth: false},"
        " {waypoints: [[2.9, -3], [2.9, 3]], speed_mps: 1.0, start_s: 46, back_and_forth: "
        "false}]"},
       {"duration_s", "150"}});
  const RunMetrics m = RunToFolder(s, dir);
  EXPECT_TRUE(fs::exists(dir / "teach_repeat_recovery.png"));
  return m.teach_repeat.value_or(TeachRepeatMetrics{});
}

TEST(TeachRepeatOcclusionTest, ThreeDRecoversTheOccludedFeaturesTwoDDoesNot) {
  const TeachRepeatMetrics t3 = RunShortRoom("3d");
  EXPECT_EQ(t3.status, "finished");
  ASSERT_EQ(t3.places.size(), 3u);
  for (const TeachRepeatMetrics::Place& p : t3.places) {
    EXPECT_GT(p.lost, 5) << "place at " << p.start_s << " s";
    EXPECT_GT(p.recovered, 0) << "place at " << p.start_s << " s";
  }
  EXPECT_GT(t3.recovery_rate, 0.5);
  EXPECT_GT(t3.recovery_rate_pooled, 0.5);

  // The 2D repeat loses the features the person passes over for good: walking across
  // the whole view 1.5 m ahead, most of the milestone's, and it finds none of them
  // again, at any place it reaches. Whether it then goes on is not recovery: as the
  // person covers them, the funnel error of those left can rise past the milestone
  // switch's hysteresis (1 px), and once too few are left to fit the progress the
  // switch takes that for the milestone passed, standing still, and goes on with the
  // next milestone's features (with the images of docs/rendering.md the error rises
  // 1.55 -> 2.87 px and the repeat finishes; with blurrier walls 1.43 -> 2.06 px and it
  // is lost: docs/results/2026-12-07-ground-sampling.md).
  const TeachRepeatMetrics t2 = RunShortRoom("2d");
  ASSERT_EQ(t2.places.size(), 3u);
  EXPECT_GT(t2.places[0].lost, 20);
  for (const TeachRepeatMetrics::Place& p : t2.places) {
    EXPECT_EQ(p.recovered, 0) << "place at " << p.start_s << " s";
  }
  EXPECT_EQ(t2.features_recovered, 0);
}

TEST(TeachRepeatOcclusionTest, ACrossingThatNeverEndsIsRejected) {
  try {
    LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/tr_occlusion.yaml",
                 {{"teach_repeat.occluders[0].back_and_forth", "true"}});
    FAIL() << "a back-and-forth crossing must be rejected";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("teach_repeat.occluders[0].back_and_forth: must be false"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace trackbed::runner
