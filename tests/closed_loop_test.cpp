// The steppable closed loop: driven step by step from outside it writes the run
// folder `trackbed run` writes, and a user's own commander drives it.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "replay_commander.h"
#include "test_scenarios.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {
namespace {

namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("trackbed_closed_loop_test_" + name);
  fs::remove_all(dir);
  return dir;
}

std::string Read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// metrics.json without the fields that measure the machine, not the run.
nlohmann::json RunFigures(const fs::path& metrics_json) {
  nlohmann::json j = nlohmann::json::parse(Read(metrics_json));
  for (const char* key : {"wall_time_s", "real_time_factor", "timing", "memory"}) j.erase(key);
  return j;
}

// Every file of `a` is in `b` with the same bytes (metrics.json: the same run figures).
void ExpectSameFolder(const fs::path& a, const fs::path& b) {
  int files = 0;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(a)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), a);
    ASSERT_TRUE(fs::exists(b / rel)) << rel;
    if (rel == "metrics.json") {
      EXPECT_EQ(RunFigures(a / rel), RunFigures(b / rel));
    } else {
      EXPECT_TRUE(Read(a / rel) == Read(b / rel)) << rel << " differs";
    }
    ++files;
  }
  EXPECT_GE(files, 15);  // logs, estimates, plots, calibration, scenario, metrics
}

TEST(ClosedLoopTest, SteppedFromOutsideItWritesTheFolderTrackbedRunWrites) {
  const std::string corridor = std::string(TRACKBED_SOURCE_DIR) + "/scenes/corridor.yaml";
  const fs::path by_command = FreshDir("command"), by_steps = FreshDir("steps");
  const std::string command = std::string(TRACKBED_BINARY) + " run " + corridor + " --out " +
                              by_command.string() + " --set duration_s=3 > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;

  ClosedLoopOptions options;
  options.dir = by_steps;
  ClosedLoop loop(scenario::LoadScenario(corridor, {{"duration_s", "3"}}), std::move(options));
  loop.Start();
  int steps = 0;
  std::size_t encoder_readings = 0;
  std::int64_t stereo_frames = 0;
  double t_s = -1.0;
  while (!loop.done()) {
    const StepResult r = loop.Step();
    EXPECT_GT(r.t_s, t_s);
    t_s = r.t_s;
    encoder_readings += r.encoders.size();
    stereo_frames += r.stereo_frames;
    ++steps;
  }
  const RunMetrics m = loop.Finish();
  EXPECT_TRUE(m.completed);
  EXPECT_EQ(m.stop_reason, "duration reached");
  // 3 s at the drive's 20 Hz, and the last step: the sensors' samples at t = 3 s.
  EXPECT_EQ(steps, 61);
  EXPECT_EQ(stereo_frames, 31);    // t = 0, 0.1, …, 3 s at the camera's 10 Hz
  EXPECT_EQ(m.stereo_frames, 31);  // the same frames the metrics count
  // Every encoder reading a step returned is a line of encoders.csv (header aside).
  const std::string encoders = Read(by_steps / "encoders.csv");
  EXPECT_EQ(encoder_readings + 1,
            static_cast<std::size_t>(std::count(encoders.begin(), encoders.end(), '\n')));
  ExpectSameFolder(by_command, by_steps);
}

TEST(ClosedLoopTest, AUsersCommanderReplaysRecordedTrackSpeeds) {
  // The scenario's own script: straight, an arc, a turn on the spot, a stop.
  scenario::Scenario s = testing::FlatTrackSpeedRun("grass", 0.3, 0.3, 1.0);
  s.duration_s = 4.0;
  s.robot.stereo.enabled = false;
  const double changes[][3] = {{0.0, 0.3, 0.3}, {1.0, 0.2, 0.4}, {2.0, -0.2, 0.2}, {3.0, 0, 0}};
  s.drive.script.clear();
  const fs::path csv = FreshDir("replay_csv");
  fs::create_directories(csv);
  std::ofstream rows(csv / "speeds.csv");
  rows << "t,left_mps,right_mps\n";
  for (const auto& c : changes) {
    scenario::DriveCommand d;
    d.t_s = c[0];
    d.track_speeds = true;
    d.left_mps = c[1];
    d.right_mps = c[2];
    s.drive.script.push_back(d);
    rows << c[0] << "," << c[1] << "," << c[2] << "\n";
  }
  rows.close();

  const fs::path scripted = FreshDir("scripted"), replayed = FreshDir("replayed");
  ClosedLoopOptions own;
  own.dir = scripted;
  const RunMetrics a = ClosedLoop(s, std::move(own)).Run();
  ClosedLoopOptions user;
  user.dir = replayed;
  user.commander = std::make_unique<testing::ReplayCommander>((csv / "speeds.csv").string(),
                                                              1.0 / s.drive.rate_hz);
  const RunMetrics b = ClosedLoop(s, std::move(user)).Run();

  EXPECT_GT(a.distance_m, 0.5);  // the commands did drive the robot
  EXPECT_EQ(a.distance_m, b.distance_m);
  EXPECT_EQ(Read(scripted / "ground_truth.tum"), Read(replayed / "ground_truth.tum"));
  EXPECT_EQ(Read(scripted / "encoders.csv"), Read(replayed / "encoders.csv"));
}

TEST(ClosedLoopTest, AnEstimateReportedFromOutsideIsScoredBesideTheStack) {
  scenario::Scenario s = testing::FlatTrackSpeedRun("grass", 0.3, 0.25, 2.0);
  s.robot.stereo.enabled = false;
  s.drive = scenario::DriveSpec();  // a commander from outside needs no drive section
  EXPECT_THROW(s.Validate(), std::invalid_argument);
  s.Validate(scenario::DriveSource::kExternal);
  // The estimate: the truth 0.1 m to the side, a horizontal error of 0.1 m all along.
  const fs::path dir = FreshDir("reported"), csv = FreshDir("reported_speeds");
  fs::create_directories(csv);
  std::ofstream(csv / "speeds.csv") << "t,left_mps,right_mps\n0,0.3,0.25\n";
  ClosedLoopOptions options;
  options.dir = dir;
  options.commander =
      std::make_unique<testing::ReplayCommander>((csv / "speeds.csv").string(), 0.05);
  ClosedLoop loop(s, std::move(options));
  loop.Start();
  int steps = 0;
  while (!loop.done()) {
    const StepResult& r = loop.Step();
    Eigen::Isometry3d estimate = r.T_world_body;
    estimate.translation() += r.T_world_body.linear() * Eigen::Vector3d(0, 0.1, 0);
    loop.ReportEstimate("mine", estimate.matrix());
    ++steps;
  }
  EXPECT_THROW(loop.ReportEstimate("mine", Eigen::Matrix4d::Identity()), std::invalid_argument);
  EXPECT_THROW(loop.ReportEstimate("fused", Eigen::Matrix4d::Identity()), std::invalid_argument);
  Eigen::Matrix4d scaled = Eigen::Matrix4d::Identity();
  scaled(0, 0) = 1.1;
  EXPECT_THROW(loop.ReportEstimate("other", scaled), std::invalid_argument);
  const RunMetrics m = loop.Finish();
  ASSERT_EQ(m.estimators.count("mine"), 1u);
  const EstimatorMetrics& mine = m.estimators.at("mine");
  EXPECT_EQ(mine.samples, steps);
  EXPECT_NEAR(mine.ate_rmse_m, 0.1, 1e-6);
  EXPECT_NEAR(mine.final_error_m, 0.1, 1e-6);
  EXPECT_EQ(m.estimators.count("wheel_odometry"), 1u);
  EXPECT_TRUE(fs::exists(dir / "mine.tum"));
  const nlohmann::json j = nlohmann::json::parse(Read(dir / "metrics.json"));
  EXPECT_EQ(j["estimators"]["mine"]["samples"], steps);
}

TEST(ClosedLoopTest, APosePathCarriesTheRobotAlongItsCurveAndEndsTheRunAtItsEnd) {
  scenario::Scenario s = testing::FlatTrackSpeedRun("paving", 0.3, 0.3, 1.0);
  s.robot.stereo.enabled = false;
  s.scene.terrain.extent_m = {-5, -30, 45, 30};
  s.scene.terrain.cell_size_m = 0.5;
  s.robot.realism = robot::Realism::kIdeal;
  s.drive = scenario::DriveSpec();
  s.drive.mode = scenario::DriveSpec::Mode::kPosePath;
  s.drive.waypoints = {{0, 0}, {20, 0}, {30, 5}, {40, 5}};
  s.drive.pursuit.speed_mps = 15.0;
  s.duration_s = 10.0;
  s.estimation.icr_expansion = 1.0;  // the carrier's virtual tracks turn without skidding
  const fs::path dir = FreshDir("pose_path");
  ClosedLoopOptions options;
  options.dir = dir;
  const RunMetrics m = ClosedLoop(s, std::move(options)).Run();
  // About 41.4 m of curve at 15 m/s: the run ends when the path does, not at 10 s.
  EXPECT_EQ(m.stop_reason, "path finished");
  EXPECT_NEAR(m.distance_m, 41.4, 0.3);
  // The last true pose is the last waypoint, heading along the curve's last tangent.
  std::ifstream truth(dir / "ground_truth.tum");
  std::string line, last;
  while (std::getline(truth, line)) last = line;
  double t, x, y, z;
  std::istringstream(last) >> t >> x >> y >> z;
  EXPECT_NEAR(x, 40.0, 1e-6);
  EXPECT_NEAR(y, 5.0, 1e-6);
  EXPECT_NEAR(t, m.distance_m / 15.0, 0.06);
  // Tracks that do not slip, and encoders that count them: the no-slip odometry of the
  // design's robot follows the truth to within the encoders' resolution.
  EXPECT_NEAR(m.encoder_distance_m, m.distance_m, 1e-3);
  EXPECT_LT(m.estimators.at("wheel_odometry_noslip").ate_rmse_m, 0.05);
}

TEST(ClosedLoopTest, StepOutsideStartAndFinishIsAnError) {
  ClosedLoop loop(testing::FlatTrackSpeedRun("hard_floor", 0.2, 0.2, 0.1));
  EXPECT_THROW(loop.Step(), std::logic_error);
  loop.Start();
  loop.Step();
  loop.Finish();
  EXPECT_THROW(loop.Step(), std::logic_error);
  EXPECT_THROW(loop.Finish(), std::logic_error);
}

}  // namespace
}  // namespace trackbed::runner
