// An SDF world in the closed loop: the robot driven at a static model's box stops with
// its hull at the box's face (Bullet), and the range sensor's beam straight ahead
// returns the face (docs/gazebo_users.md).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/description/sdf_world.h"
#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

void Write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// The first data row of a CSV file, as numbers.
std::vector<double> FirstRow(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::vector<double> row;
  std::istringstream cells(line);
  std::string cell;
  while (std::getline(cells, cell, ',')) {
    row.push_back(cell == "inf" ? std::numeric_limits<double>::infinity() : std::stod(cell));
  }
  return row;
}

TEST(SdfClosedLoopTest, ABoxOfTheWorldStopsTheRobotAtItsFaceAndReturnsTheBeam) {
  if (!description::CanReadDescriptions()) {
    GTEST_SKIP() << "built without sdformat (TRACKBED_WITH_SDF=OFF)";
  }
  const fs::path dir =
      fs::temp_directory_path() / ("sdf_closed_loop_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  // A crate 0.6 m deep and 3 m wide, its near face 3 m ahead of the start, placed through
  // a frame.
  Write(dir / "world.sdf", R"(<?xml version='1.0'?>
<sdf version='1.9'><world name='w'>
  <frame name='row'><pose>2 0 0 0 0 0</pose></frame>
  <model name='crate'><static>true</static><pose relative_to='row'>1.3 0 0.5 0 0 0</pose>
    <link name='l'>
      <visual name='v'><geometry><box><size>0.6 3 1</size></box></geometry></visual>
      <collision name='c'><geometry><box><size>0.6 3 1</size></box></geometry></collision>
    </link></model>
</world></sdf>
)");
  Write(dir / "scenario.yaml",
        "duration_s: 12\n"
        "drive:\n  speed_mps: 0.5\n  waypoints: [[0, 0], [8, 0]]\n"
        "robot:\n  range_sensor: {enabled: true, beams: 8, noise_std_m: 0}\n"
        "scene:\n  terrain: {extent_m: [-5, -5, 10, 5]}\n  sdf: {file: world.sdf}\n");
  const scenario::Scenario s = scenario::LoadScenario((dir / "scenario.yaml").string());
  ASSERT_EQ(s.scene.objects.size(), 1u);
  runner::RunToFolder(s, dir / "run");
  std::ifstream tum(dir / "run" / "ground_truth.tum");
  std::string line;
  double furthest = -1e9, x0 = std::nan("");
  while (std::getline(tum, line)) {
    std::istringstream in(line);
    double t, x;
    in >> t >> x;
    if (std::isnan(x0)) x0 = x;
    furthest = std::max(furthest, x);
  }
  const std::vector<double> scan = FirstRow(dir / "run" / "scan.csv");
  ASSERT_GT(scan.size(), 5u);
  std::printf(
      "furthest body x %.4f m (hull front %.4f m, the face at 3 m); first beam ahead "
      "%.4f m, expected %.4f m\n",
      furthest, furthest + 0.35, scan[1], 3.0 - 0.2 - x0);
  // The hull's front (0.35 m ahead of its centre) reaches the face at x = 3 and stays.
  EXPECT_GT(furthest, 3.0 - 0.35 - 0.1);
  EXPECT_LT(furthest, 3.0 - 0.35 + 0.02);
  // The first scan: straight ahead the face, from the sensor 0.2 m ahead of the body.
  EXPECT_NEAR(scan[1], 3.0 - 0.2 - x0, 1e-3);
  EXPECT_TRUE(std::isinf(scan[5]));  // behind: nothing within 8 m
  fs::remove_all(dir);
}

}  // namespace
}  // namespace trackbed
