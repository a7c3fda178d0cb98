// The run folder's streamed logs: a run killed at any point leaves files of whole lines,
// and outputs.decimate thins the high-rate logs, not the metrics.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "trackbed/runner/closed_loop.h"
#include "trackbed/runner/log_file.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {
namespace {

namespace fs = std::filesystem;

fs::path Fresh(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("trackbed_run_logs_test_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::size_t Lines(const fs::path& file, std::string* last = nullptr) {
  std::ifstream in(file);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line); ++n) {
    if (last) *last = line;
  }
  return n;
}

TEST(LogFileTest, AProcessKilledMidStreamLeavesWholeLines) {
  const fs::path file = Fresh("kill") / "imu.csv";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    LogFile log(file, "t,value");
    char line[64];
    for (int k = 0; k < 100000; ++k) {
      std::snprintf(line, sizeof(line), "%d.000000,%.9g", k, 0.1 * k);
      log.Line(line);
    }
    ::raise(SIGKILL);  // no Close(), no flush: as a run killed late
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  std::ifstream in(file, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');  // no partial last line
  std::string last;
  const std::size_t lines = Lines(file, &last);
  // Everything but the last buffer (64 KiB, about 3500 of these lines) is on disk.
  EXPECT_GT(lines, 100000u - 4000u);
  EXPECT_EQ(last.substr(0, last.find(',')), std::to_string(lines - 2) + ".000000");
}

nlohmann::json RunPark(const fs::path& dir, const std::string& decimate) {
  const scenario::Scenario s = scenario::LoadScenario(TRACKBED_SOURCE_DIR "/scenes/outdoor.yaml",
                                                      {{"duration_s", "10"},
                                                       {"robot.stereo.enabled", "false"},
                                                       {"outputs.mcap", "false"},
                                                       {"outputs.decimate", decimate}});
  ClosedLoopOptions options;
  options.dir = dir;
  ClosedLoop(s, std::move(options)).Run();
  std::ifstream in(dir / "metrics.json");
  nlohmann::json m = nlohmann::json::parse(in);
  for (const char* machine : {"wall_time_s", "real_time_factor", "timing", "memory"})
    m.erase(machine);
  return m;
}

TEST(RunLogsTest, DecimateThinsTheHighRateLogsNotTheMetrics) {
  const fs::path all = Fresh("all"), tenth = Fresh("tenth");
  const nlohmann::json m_all = RunPark(all, "1"), m_tenth = RunPark(tenth, "10");
  EXPECT_EQ(m_all, m_tenth);
  // 10 s: 1001 encoder samples and 2000 IMU samples, and a header row.
  EXPECT_EQ(Lines(all / "ground_truth.tum"), 1001u);
  EXPECT_EQ(Lines(tenth / "ground_truth.tum"), 101u);
  EXPECT_EQ(Lines(tenth / "ground_truth_twist.csv"), 1u + 101u);
  EXPECT_EQ(Lines(tenth / "ekf.tum"), 101u);
  EXPECT_EQ(Lines(all / "imu.csv"), 1u + 2000u);
  EXPECT_EQ(Lines(tenth / "imu.csv"), 1u + 200u);
  // Every tenth row, from the first.
  std::ifstream a(all / "encoders.csv"), t(tenth / "encoders.csv");
  std::string la, lt;
  for (int k = 0; std::getline(a, la); ++k) {
    if (k >= 1 && (k - 1) % 10 != 0) continue;  // the header, then rows 0, 10, 20, …
    ASSERT_TRUE(std::getline(t, lt));
    EXPECT_EQ(la, lt);
  }
  EXPECT_FALSE(std::getline(t, lt));
  fs::remove_all(all);
  fs::remove_all(tenth);
}

}  // namespace
}  // namespace trackbed::runner
