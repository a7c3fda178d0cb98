// Point-to-point navigation runs through the scenario file and the run folder
// (docs/navigation.md, kinematic mode): the paper's scenes reach the goal pose with a
// sub-goal, bad input ends with a clear status or a clear error, and the run
// folder holds what docs/run_folder.md promises.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {

using namespace scenario;  // the scenarios these tests run
namespace {

namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("trackbed_nav_" + name);
  fs::remove_all(dir);
  return dir;
}

nlohmann::json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

std::string ScenarioErrorOf(const std::string& text) {
  try {
    ParseScenario(text, "nav.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

// A run's progress (runner/run_progress.h) follows the encoder samples; a kinematic
// run has none, so its observers see every control step's pose instead, in order.
TEST(NavigationRunTest, KinematicRunShowsEveryControlStepToTheObservers) {
  const Scenario s = LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/nav_paper_left.yaml");
  const fs::path dir = FreshDir("observed");
  std::vector<RunSample> seen;
  RunObservers observers;
  observers.on_sample = [&seen](const RunSample& r) { seen.push_back(r); };
  const RunMetrics m = RunToFolder(s, dir, observers);
  std::ifstream truth(dir / "ground_truth.tum");
  std::string line;
  std::size_t rows = 0;
  while (std::getline(truth, line)) {
    ASSERT_LT(rows, seen.size());
    double t = 0.0, x = 0.0, y = 0.0;
    std::istringstream(line) >> t >> x >> y;
    EXPECT_NEAR(seen[rows].t_s, t, 1e-6) << rows;
    EXPECT_NEAR(seen[rows].chassis.T_world_body.translation().x(), x, 1e-6) << rows;
    EXPECT_NEAR(seen[rows].chassis.T_world_body.translation().y(), y, 1e-6) << rows;
    ++rows;
  }
  EXPECT_GT(rows, 10u);
  EXPECT_EQ(seen.size(), rows);
  EXPECT_NEAR(seen.back().t_s, m.sim_time_s, 1e-9);
}

TEST(NavigationRunTest, PaperSceneLeftReachesTheGoalPoseThroughASubgoal) {
  const Scenario s = LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/nav_paper_left.yaml");
  const fs::path dir = FreshDir("left");
  const RunMetrics m = RunToFolder(s, dir);
  ASSERT_TRUE(m.navigation.has_value());
  EXPECT_TRUE(m.navigation->success) << m.navigation->status;
  EXPECT_LE(m.navigation->final_position_error_m, 0.1);
  EXPECT_LE(m.navigation->final_heading_error_deg, 2.0);
  EXPECT_GE(m.navigation->subgoals, 1);
  EXPECT_EQ(m.navigation->collisions, 0);

  const nlohmann::json j = ReadJson(dir / "metrics.json");
  EXPECT_EQ(j["status"], "completed");
  EXPECT_EQ(j["navigation"]["method"], "gauss_newton_subgoal");
  EXPECT_EQ(j["navigation"]["success"], true);
  for (const char* key :
       {"time_to_goal_s", "path_length_m", "final_position_error_m", "final_heading_error_deg",
        "min_clearance_m", "mean_clearance_m", "collisions", "integrated_abs_jerk"}) {
    EXPECT_TRUE(j["navigation"].contains(key)) << key;
  }
  for (const char* file :
       {"scenario.yaml", "ground_truth.tum", "navigation.csv", "navigation.png"}) {
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  }
  std::ifstream csv(dir / "navigation.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("t,x_m,y_m,yaw_rad,", 0), 0u) << header;
}

TEST(NavigationRunTest, GaussNewtonPathIsShorterThanThePotentialFieldsOnBothPaperScenes) {
  for (const char* scene : {"nav_paper_left.yaml", "nav_paper_right.yaml"}) {
    const std::string path = std::string(TRACKBED_SOURCE_DIR) + "/scenes/" + scene;
    const RunMetrics gn = RunToFolder(LoadScenario(path), FreshDir("gn"));
    const RunMetrics pf =
        RunToFolder(LoadScenario(path, {{"navigation.method", "potential_field"}}), FreshDir("pf"));
    ASSERT_TRUE(gn.navigation && pf.navigation);
    EXPECT_TRUE(gn.navigation->success) << scene;
    EXPECT_TRUE(pf.navigation->success) << scene;
    EXPECT_LT(gn.navigation->path_length_m, pf.navigation->path_length_m) << scene;
  }
}

TEST(NavigationRunTest, GoalInsideAnObstacleEndsWithAClearStatus) {
  const Scenario s = ParseScenario(
      "navigation:\n  enabled: true\n  goal: {x_m: 4, y_m: 0, yaw_deg: 0}\n"
      "  obstacles:\n    - {center: [4, 0], radius_m: 0.5}\n",
      "nav.yaml");
  const RunMetrics m = RunToFolder(s, FreshDir("inside"));
  ASSERT_TRUE(m.navigation.has_value());
  EXPECT_FALSE(m.navigation->success);
  EXPECT_EQ(m.navigation->status, "goal_in_obstacle");
  EXPECT_LT(m.navigation->duration_s, 1.0);
}

TEST(NavigationRunTest, WalledInGoalStallsBeforeTheTimeLimit) {
  // A square of walls around the goal: unreachable, so the run must end "stalled".
  const Scenario s = ParseScenario(
      "duration_s: 300\n"
      "navigation:\n  enabled: true\n  goal: {x_m: 6, y_m: 0, yaw_deg: 0}\n  walls:\n"
      "    - {from: [4.5, -1.5], to: [7.5, -1.5]}\n    - {from: [7.5, -1.5], to: [7.5, 1.5]}\n"
      "    - {from: [7.5, 1.5], to: [4.5, 1.5]}\n    - {from: [4.5, 1.5], to: [4.5, -1.5]}\n",
      "nav.yaml");
  const RunMetrics m = RunToFolder(s, FreshDir("walled"));
  ASSERT_TRUE(m.navigation.has_value());
  EXPECT_FALSE(m.navigation->success);
  EXPECT_EQ(m.navigation->status, "stalled");
  EXPECT_LT(m.navigation->duration_s, 300.0);
  EXPECT_EQ(m.navigation->collisions, 0);
}

TEST(NavigationRunTest, BadNavigationKeysNameTheKey) {
  EXPECT_NE(ScenarioErrorOf("navigation:\n  enabled: true\n  method: bug2\n")
                .find("navigation.method: must be one of gauss_newton_subgoal"),
            std::string::npos);
  EXPECT_NE(
      ScenarioErrorOf("navigation:\n  enabled: true\n  field: maze\n").find("navigation.field"),
      std::string::npos);
  EXPECT_NE(ScenarioErrorOf("navigation:\n  enabled: true\n  safety_radius_m: -1\n")
                .find("navigation.safety_radius_m: must be > 0"),
            std::string::npos);
  EXPECT_NE(
      ScenarioErrorOf("navigation:\n  enabled: true\n  mode: teleport\n").find("navigation.mode"),
      std::string::npos);
  const std::string negative_tau = ScenarioErrorOf(
      "navigation:\n  enabled: true\n  gauss_newton: {final_time_constant_s: -0.1}\n");
  EXPECT_NE(negative_tau.find("nav.yaml"), std::string::npos) << negative_tau;
  EXPECT_NE(negative_tau.find("final_time_constant_s"), std::string::npos) << negative_tau;
}

TEST(NavigationRunTest, RandomFieldsComeFromTheSeed) {
  const std::string text = "navigation:\n  enabled: true\n  field: random\n  field_seed: 7\n";
  const RunMetrics a = RunToFolder(ParseScenario(text, "nav.yaml"), FreshDir("rand_a"));
  const RunMetrics b = RunToFolder(ParseScenario(text, "nav.yaml"), FreshDir("rand_b"));
  ASSERT_TRUE(a.navigation && b.navigation);
  EXPECT_EQ(a.navigation->path_length_m, b.navigation->path_length_m);
  EXPECT_TRUE(a.navigation->success) << a.navigation->status;
}

}  // namespace
}  // namespace trackbed::runner
