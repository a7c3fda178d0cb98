// Mesh objects in the closed loop: a wall read from an OBJ file stops the robot
// through Bullet and returns the range sensor's beams; a ground mesh is driven on.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mesh_files.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/runner/run_scenario.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/terrain.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

// The rows of a CSV file after its header, as numbers.
std::vector<std::vector<double>> Rows(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      row.push_back(cell == "inf" ? std::numeric_limits<double>::infinity() : std::stod(cell));
    }
    rows.push_back(row);
  }
  return rows;
}

// The (x, z) of each ground-truth pose.
std::vector<Eigen::Vector3d> TruePositions(const fs::path& dir) {
  std::ifstream tum(dir / "ground_truth.tum");
  std::vector<Eigen::Vector3d> out;
  std::string line;
  while (std::getline(tum, line)) {
    std::istringstream in(line);
    double t, x, y, z;
    in >> t >> x >> y >> z;
    out.emplace_back(x, y, z);
  }
  return out;
}

TEST(MeshClosedLoopTest, AMeshWallStopsTheRobotAndReturnsTheRangeSensorsBeams) {
  // A wall 0.3 m thick, 4 m wide and 1 m high, its near face 3 m ahead of the start.
  test_mesh::ObjBox("wall_drive.obj", 0, -2, 0, 0.3, 2, 1);
  const fs::path dir = fs::path(testing::TempDir()) / "mesh_wall_drive";
  const std::string yaml =
      test_mesh::Write("mesh_wall_drive.yaml",
                       "duration_s: 12\n"
                       "drive:\n  speed_mps: 0.5\n  waypoints: [[0, 0], [8, 0]]\n"
                       "robot:\n  range_sensor: {enabled: true, beams: 8, noise_std_m: 0}\n"
                       "scene:\n  terrain: {extent_m: [-5, -5, 10, 5]}\n"
                       "  objects:\n    - {type: mesh, file: wall_drive.obj, center: [3, 0]}\n");
  const scenario::Scenario s = scenario::LoadScenario(yaml);
  runner::RunToFolder(s, dir);
  const std::vector<Eigen::Vector3d> path = TruePositions(dir);
  ASSERT_GT(path.size(), 100u);
  double furthest = -1e9;
  for (const Eigen::Vector3d& p : path) furthest = std::max(furthest, p.x());
  // The hull's front (0.35 m ahead of its centre) reaches the wall and stays there.
  EXPECT_GT(furthest, 3.0 - 0.35 - 0.1);
  EXPECT_LT(furthest, 3.0 - 0.35 + 0.02);
  // The first scan, at the start: straight ahead the wall's face, 3 m from the body
  // and 2.8 m from the sensor (mounted 0.2 m forward); behind, nothing within 8 m.
  const std::vector<std::vector<double>> scans = Rows(dir / "scan.csv");
  ASSERT_FALSE(scans.empty());
  const double x0 = path.front().x();
  EXPECT_NEAR(scans.front()[1], 3.0 - 0.2 - x0, 1e-3);
  EXPECT_TRUE(std::isinf(scans.front()[5]));
  // The run folder fingerprints the mesh file.
  std::ifstream inputs(dir / "inputs.json");
  std::stringstream text;
  text << inputs.rdbuf();
  EXPECT_NE(text.str().find("\"key\": \"scene.objects[0].file\""), std::string::npos) << text.str();
}

// An arch 3 m ahead (its opening 1.2 m wide, 0.7 m high: the hull is 0.42 m wide and
// 0.28 m high, the tracks' outer edges 0.6 m apart) driven through, or, with its
// bounding box as the collision solid, driven into.
std::vector<Eigen::Vector3d> DriveAtArch(const std::string& collision) {
  test_mesh::ObjArch("arch.obj");
  const fs::path dir = fs::path(testing::TempDir()) / ("mesh_arch_" + collision);
  const std::string yaml = test_mesh::Write(
      "mesh_arch_" + collision + ".yaml",
      "duration_s: 14\n"
      "drive:\n  speed_mps: 0.5\n  waypoints: [[0, 0], [6, 0]]\n"
      "robot:\n  range_sensor: {enabled: true, noise_std_m: 0}\n"
      "scene:\n  terrain: {extent_m: [-5, -5, 10, 5]}\n"
      "  objects:\n    - {type: mesh, file: arch.obj, center: [3, 0], collision: " +
          collision + "}\n");
  runner::RunToFolder(scenario::LoadScenario(yaml), dir);
  return TruePositions(dir);
}

TEST(MeshClosedLoopTest, TheRobotDrivesUnderAnArchTheRangeSensorSeesThrough) {
  const std::vector<Eigen::Vector3d> path = DriveAtArch("mesh");
  ASSERT_GT(path.size(), 100u);
  double furthest = -1e9, widest = 0.0;
  for (const Eigen::Vector3d& p : path) {
    furthest = std::max(furthest, p.x());
    widest = std::max(widest, std::abs(p.y()));
  }
  EXPECT_GT(furthest, 5.5);  // through the arch, untouched
  EXPECT_LT(widest, 0.05);
  // The first scan: straight ahead through the opening, nothing within 8 m; 13° to the
  // left the pillar's face at x = 3 (y 0.646 m there), 2.8 m ahead of the sensor.
  const std::vector<std::vector<double>> scans =
      Rows(fs::path(testing::TempDir()) / "mesh_arch_mesh" / "scan.csv");
  ASSERT_FALSE(scans.empty());
  EXPECT_TRUE(std::isinf(scans.front()[1]));
  EXPECT_NEAR(scans.front()[1 + 13], (2.8 - path.front().x()) / std::cos(13 * M_PI / 180), 2e-3);
  EXPECT_NEAR(scans.front()[1 + 360 - 13], scans.front()[1 + 13], 1e-6);
  // Its bounding box as the solid: the hull stops at the arch's face.
  double stopped = -1e9;
  for (const Eigen::Vector3d& p : DriveAtArch("box")) stopped = std::max(stopped, p.x());
  EXPECT_LT(stopped, 3.0 - 0.35 + 0.02);
}

TEST(MeshClosedLoopTest, TheTracksDriveOnAGroundMeshAtItsHeights) {
  // A ramp: flat for x < 2, rising 10 % from x = 2 to 12, two facets per face.
  test_mesh::Write("ramp.obj",
                   "v -6 -6 0\nv 2 -6 0\nv 2 6 0\nv -6 6 0\nv 14 -6 1.2\nv 14 6 1.2\n"
                   "f 1 2 3 4\nf 2 5 6 3\n");
  const fs::path dir = fs::path(testing::TempDir()) / "mesh_ramp_drive";
  const std::string yaml =
      test_mesh::Write("mesh_ramp_drive.yaml",
                       "duration_s: 20\n"
                       "drive:\n  speed_mps: 0.6\n  waypoints: [[0, 0], [9, 0]]\n"
                       "scene:\n  terrain: {extent_m: [-5, -5, 13, 5]}\n"
                       "  objects:\n    - {type: mesh, file: ramp.obj, ground: true}\n");
  const scenario::Scenario s = scenario::LoadScenario(yaml);
  runner::RunToFolder(s, dir);
  const std::vector<Eigen::Vector3d> path = TruePositions(dir);
  ASSERT_GT(path.size(), 100u);
  const auto ramp = [](double x) { return x < 2.0 ? 0.0 : 0.1 * (x - 2.0); };
  double lo = 1e9, hi = -1e9;
  for (const Eigen::Vector3d& p : path) {
    const double above = p.z() - ramp(p.x());
    lo = std::min(lo, above);
    hi = std::max(hi, above);
  }
  EXPECT_GT(path.back().x(), 7.0);  // it drove up the ramp
  // The body's height above the mesh stays within the suspension's play: it stands on
  // the mesh's heights, not on flat ground (0.5 m below at the end).
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi - lo, 0.05) << "height above the mesh from " << lo << " to " << hi << " m";
}

}  // namespace
}  // namespace trackbed
