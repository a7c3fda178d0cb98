// Teach & repeat on rough ground (scenes/tr_outdoor.yaml): Chen & Birchfield
// claim the funnel lane works outdoors on rough terrain. On undulating, bumpy grass and
// a stretch of dry sand, where the bang-bang steering makes the tracks slip, the 2D
// repeat of the route's last 5.6 m still completes and its lateral error against the
// taught ground truth stays bounded.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {

using namespace scenario;  // the scenarios these tests run
namespace {

namespace fs = std::filesystem;

TEST(TeachRepeatOutdoorTest, OnRoughGroundWithSlipTheRepeatStaysOnTheRoute) {
  const fs::path dir = fs::path(testing::TempDir()) / "trackbed_tr_outdoor";
  fs::remove_all(dir);
  // The shipped route from x = 2 m: 1 m straight, the 60° curve, 1.8 m onto the sand.
  const Scenario s =
      LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/tr_outdoor.yaml",
                   {{"robot.start", "{x_m: 2, y_m: 0, yaw_deg: 0}"},
                    {"drive.waypoints",
                     "[[2, 0], [3, 0], [3.776, 0.102], [4.5, 0.402], [5.121, 0.879], [5.598, 1.5], "
                     "[6.5, 3.062]]"},
                    {"duration_s", "150"}});
  const RunMetrics m = RunToFolder(s, dir);
  ASSERT_TRUE(m.teach_repeat.has_value());
  const TeachRepeatMetrics& t = *m.teach_repeat;
  EXPECT_EQ(t.status, "finished");
  EXPECT_TRUE(t.completed);
  EXPECT_GT(t.taught_length_m, 5.0);
  // The map's size on disk, as a user sizes a long route's map by it.
  EXPECT_GT(t.map_size_mb, 0.01 * t.milestones);  // a key image per milestone at least
  EXPECT_NEAR(t.map_mb_per_100m, t.map_size_mb * 100.0 / t.taught_length_m, 1e-12);
  EXPECT_LT(t.lateral_rms_m, 0.15);
  EXPECT_LT(t.lateral_max_m, 0.25);
  EXPECT_LT(t.end_point_error_m, 0.25);
  // The images pass every milestone here: the distance bound is for ground whose images
  // cannot (docs/teach_repeat.md, "Distance bound").
  EXPECT_EQ(t.switches_by_distance, 0);
  // The repeat crossed the sand and slipped there.
  ASSERT_TRUE(m.slip_by_material.count("dry_sand"));
  EXPECT_GT(m.slip_by_material.at("dry_sand").mean_abs_ratio(), 0.02);
}

}  // namespace
}  // namespace trackbed::runner
