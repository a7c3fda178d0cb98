// Teach & repeat through `trackbed run` (docs/teach_repeat.md): one run teaches a short route in a
// textured room and repeats it from the images; the saved map can be repeated again by
// a later run; a bad map is a clear error. Scored against the taught ground truth.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {

using namespace scenario;  // the scenarios these tests run
namespace {

namespace fs = std::filesystem;

// tr_lab's room, a 4 m route with a gentle left curve, taught at 0.1 m/s.
Scenario ShortRoute(const std::string& method, const std::vector<Override>& more = {}) {
  std::vector<Override> overrides = {
      {"drive.waypoints", "[[0, 0], [2, 0], [2.6, 0.1], [3.1, 0.4], [3.6, 0.9]]"},
      {"teach_repeat.method", method},
      {"duration_s", "150"}};
  overrides.insert(overrides.end(), more.begin(), more.end());
  return LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/tr_lab.yaml", overrides);
}

TEST(TeachRepeatRunTest, TwoDRepeatFollowsTheTaughtRouteAndItsMapRepeatsAgain) {
  const fs::path dir = fs::path(testing::TempDir()) / "trackbed_tr_2d";
  fs::remove_all(dir);
  const RunMetrics m = RunToFolder(ShortRoute("2d"), dir);
  ASSERT_TRUE(m.teach_repeat.has_value());
  const TeachRepeatMetrics& t = *m.teach_repeat;
  EXPECT_EQ(t.status, "finished");
  EXPECT_TRUE(t.completed);
  EXPECT_DOUBLE_EQ(t.autonomy, 1.0);
  EXPECT_LT(t.lateral_rms_m, 0.10);
  EXPECT_LT(t.end_point_error_m, 0.15);
  EXPECT_GE(t.milestones, 5);
  for (const char* f : {"teach/ground_truth.tum", "teach_map/map.json", "teach_repeat.png",
                        "ground_truth.tum", "metrics.json"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  // A later run repeats the saved map without teaching, scored against teach/ beside it.
  const fs::path again = fs::path(testing::TempDir()) / "trackbed_tr_2d_again";
  fs::remove_all(again);
  const RunMetrics m2 =
      RunToFolder(ShortRoute("2d", {{"teach_repeat.map", (dir / "teach_map").string()}}), again);
  ASSERT_TRUE(m2.teach_repeat.has_value());
  EXPECT_FALSE(fs::exists(again / "teach"));
  EXPECT_EQ(m2.teach_repeat->status, "finished");
  EXPECT_EQ(m2.teach_repeat->milestones, t.milestones);
  EXPECT_LT(m2.teach_repeat->lateral_rms_m, 0.10);
}

TEST(TeachRepeatRunTest, AMissingOrCorruptMapIsAClearError) {
  try {
    ShortRoute("2d", {{"teach_repeat.map", "/nonexistent/teach_map"}});
    FAIL() << "a missing map folder must be rejected when the scenario loads";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("teach_repeat.map: no such folder"), std::string::npos)
        << e.what();
  }
  const fs::path bad = fs::path(testing::TempDir()) / "trackbed_tr_bad_map";
  fs::remove_all(bad);
  fs::create_directories(bad);
  std::ofstream(bad / "map.json") << "{\"format\": \"something else\"}";
  const Scenario s = ShortRoute("2d", {{"teach_repeat.map", bad.string()}});
  try {
    RunToFolder(s, fs::path(testing::TempDir()) / "trackbed_tr_bad_run");
    FAIL() << "a corrupt map must not run";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("map.json"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace trackbed::runner
