// What a crash leaves, and that a resume recovers from it: a run and a sweep killed with
// SIGKILL at chosen durable steps (TRACKBED_TEST_KILL_AT, common/durable_file.h: the
// process kills itself just before or after a file that marks something finished is
// renamed into place, so the kill lands at the step named, never after a sleep), a
// sweep stopped by SIGTERM, a second sweep started on a folder in use, and a finished
// cell's record deleted. After each, a resume gives the same summary and report as a
// sweep that was never interrupted, and no finished cell runs again.
#include <signal.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "process_control.h"
#include "trackbed/common/durable_file.h"

namespace {

namespace fs = std::filesystem;
using trackbed::testing_cli::DeterministicColumns;
using trackbed::testing_cli::RunTrackbed;
using trackbed::testing_cli::Slurp;

const fs::path kSource = TRACKBED_SOURCE_DIR;

fs::path TempDir(const std::string& name) {
  return trackbed::testing_cli::FreshTempDir("trackbed_crash_recovery_test_", name);
}

// TRACKBED_TEST_KILL_AT for the commands this test starts while it lives.
class KillAt {
 public:
  explicit KillAt(const std::string& spec) { ::setenv(trackbed::kKillAtVariable, spec.c_str(), 1); }
  ~KillAt() { ::unsetenv(trackbed::kKillAtVariable); }
  KillAt(const KillAt&) = delete;
  KillAt& operator=(const KillAt&) = delete;
};

// The shell's status of a command killed by SIGKILL.
constexpr int kKilledBySigkill = 128 + SIGKILL;

std::string RunArgs(const fs::path& out) {
  return "run scenes/corridor.yaml --set duration_s=2 --out '" + out.string() + "'";
}

// Killed before metrics.json is renamed into place: the run's files are whole and the
// same as an uninterrupted run's, its result complete in the synced temporary file, and
// no metrics.json says it finished. Killed just after, the result is there.
TEST(CrashRecoveryTest, ARunKilledAtItsMetricsRenameLeavesWholeFiles) {
  const fs::path dir = TempDir("run");
  const auto whole = RunTrackbed(RunArgs(dir / "whole"), dir / "io0");
  ASSERT_EQ(whole.exit_code, 0) << whole.stderr_text;
  {
    const KillAt kill("before_rename:metrics.json");
    const auto r = RunTrackbed(RunArgs(dir / "cut"), dir / "io1");
    ASSERT_EQ(r.exit_code, kKilledBySigkill) << r.stderr_text;
  }
  EXPECT_FALSE(fs::exists(dir / "cut" / "metrics.json"));
  const nlohmann::json pending = nlohmann::json::parse(Slurp(dir / "cut" / "metrics.json.tmp"));
  EXPECT_EQ(pending["status"], "completed");
  const nlohmann::json done = nlohmann::json::parse(Slurp(dir / "whole" / "metrics.json"));
  EXPECT_EQ(pending["estimators"]["fused"]["ate_rmse_m"],
            done["estimators"]["fused"]["ate_rmse_m"]);
  for (const char* file : {"ground_truth.tum", "encoders.csv", "imu.csv", "fused.tum",
                           "visual_odometry.tum", "fusion.csv", "run.mcap", "metadata.yaml"}) {
    EXPECT_FALSE(Slurp(dir / "whole" / file).empty()) << file;
    EXPECT_EQ(Slurp(dir / "cut" / file), Slurp(dir / "whole" / file)) << file;
  }
  {
    const KillAt kill("after_rename:metrics.json");
    const auto r = RunTrackbed(RunArgs(dir / "late"), dir / "io2");
    ASSERT_EQ(r.exit_code, kKilledBySigkill) << r.stderr_text;
  }
  const nlohmann::json late = nlohmann::json::parse(Slurp(dir / "late" / "metrics.json"));
  EXPECT_EQ(late["status"], "completed");
  EXPECT_FALSE(fs::exists(dir / "late" / "metrics.json.tmp"));
}

// Two cells of the corridor for 3 simulated seconds, one at a time.
class SweepCrashTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = TempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    file_ = dir_ / "short.yaml";
    std::ofstream(file_) << "name: short\n"
                         << "scenarios: [" << (kSource / "scenes/corridor.yaml").string() << "]\n"
                         << "seeds: [1, 2]\n"
                         << "set: [\"duration_s=3\"]\n"
                         << "timeout_s: 300\n";
    const auto r = Sweep(dir_ / "whole", "whole");
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  }

  trackbed::testing_cli::CliResult Sweep(const fs::path& out, const std::string& io) const {
    return RunTrackbed("sweep '" + file_.string() + "' --out '" + out.string() + "' --jobs 1",
                       dir_ / ("io_" + io));
  }

  // A resume of `out` says how many cells had finished, ends well and gives the
  // uninterrupted sweep's summary and report.
  void ExpectResumesToTheWhole(const fs::path& out, int finished, const std::string& why) const {
    const auto r = Sweep(out, "resume");
    EXPECT_EQ(r.exit_code, 0) << why << ": " << r.stderr_text;
    const std::string counts = "2 cells, " + std::to_string(finished) + " finished already, " +
                               std::to_string(2 - finished) + " to run";
    EXPECT_NE(r.stderr_text.find(counts), std::string::npos) << why << ": " << r.stderr_text;
    EXPECT_EQ(DeterministicColumns(out / "summary.csv"),
              DeterministicColumns(dir_ / "whole" / "summary.csv"))
        << why;
    EXPECT_EQ(Slurp(out / "report.md"), Slurp(dir_ / "whole" / "report.md")) << why;
  }

  fs::path dir_, file_;
};

std::string Cell(int seed) { return "corridor__seed-" + std::to_string(seed); }

TEST_F(SweepCrashTest, KilledAtEachDurableStepItResumesWithoutRerunningFinishedCells) {
  struct Case {
    std::string kill_at;  // TRACKBED_TEST_KILL_AT for the first attempt
    int exit_code;        // of the first attempt: the sweep killed, or a cell
    int finished;         // cells a resume finds finished
  };
  const std::vector<Case> cases = {
      // The sweep, between cell 1's run and its record, then just after the record.
      {"before_rename:" + Cell(1) + "/cell.json", kKilledBySigkill, 1},
      {"after_rename:" + Cell(1) + "/cell.json", kKilledBySigkill, 1},
      // Cell 2's run, before its result is visible (failed, rerun) and just after (ok).
      {"before_rename:" + Cell(2) + "/run/metrics.json", 1, 1},
      {"after_rename:" + Cell(2) + "/run/metrics.json", 0, 2},
      // The sweep, writing its summary after every cell finished.
      {"before_rename:/summary.csv", kKilledBySigkill, 2},
  };
  int n = 0;
  for (const Case& c : cases) {
    const fs::path out = dir_ / ("cut" + std::to_string(n++));
    {
      const KillAt kill(c.kill_at);
      const auto r = Sweep(out, "cut");
      ASSERT_EQ(r.exit_code, c.exit_code) << c.kill_at << ": " << r.stderr_text;
    }
    const std::string first_metrics = Slurp(out / "cells" / Cell(1) / "run" / "metrics.json");
    ASSERT_FALSE(first_metrics.empty()) << c.kill_at;
    ExpectResumesToTheWhole(out, c.finished, c.kill_at);
    // Cell 1 had finished: the resume did not run it again.
    EXPECT_EQ(Slurp(out / "cells" / Cell(1) / "run" / "metrics.json"), first_metrics) << c.kill_at;
  }
}

TEST_F(SweepCrashTest, ASweepStoppedBySigtermResumes) {
  const fs::path out = dir_ / "cut";
  const pid_t pid = trackbed::testing_process::Spawn(
      {"sweep", file_.string(), "--out", out.string(), "--jobs", "1"}, dir_ / "io_term");
  ASSERT_TRUE(trackbed::testing_process::WaitForFile(out / "cells" / Cell(2) / "stderr.txt", pid));
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM) << Slurp(dir_ / "io_term" / "err");
  EXPECT_NE(Slurp(dir_ / "io_term" / "err").find("interrupted by signal 15"), std::string::npos)
      << Slurp(dir_ / "io_term" / "err");
  ExpectResumesToTheWhole(out, 1, "SIGTERM");
}

TEST_F(SweepCrashTest, ASecondSweepOnAFolderInUseIsRefusedAndChangesNothing) {
  const fs::path out = dir_ / "busy";
  const pid_t pid = trackbed::testing_process::Spawn(
      {"sweep", file_.string(), "--out", out.string(), "--jobs", "1"}, dir_ / "io_first");
  ASSERT_TRUE(trackbed::testing_process::WaitForFile(out / "cells" / Cell(1) / "stderr.txt", pid));
  const auto second = Sweep(out, "second");
  EXPECT_EQ(second.exit_code, 2);
  EXPECT_NE(second.stderr_text.find("another `trackbed sweep` is running there"), std::string::npos)
      << second.stderr_text;
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << Slurp(dir_ / "io_first" / "err");
  EXPECT_EQ(DeterministicColumns(out / "summary.csv"),
            DeterministicColumns(dir_ / "whole" / "summary.csv"));
  // Once the first has ended the folder is free again.
  ExpectResumesToTheWhole(out, 2, "after the first sweep");
}

TEST_F(SweepCrashTest, AFinishedCellsDeletedRecordIsRecoveredFromItsRun) {
  const fs::path out = dir_ / "copy";
  fs::copy(dir_ / "whole", out, fs::copy_options::recursive);
  const fs::path record = out / "cells" / Cell(1) / "cell.json";
  const nlohmann::json before = nlohmann::json::parse(Slurp(record));
  const std::string metrics = Slurp(out / "cells" / Cell(1) / "run" / "metrics.json");
  fs::remove(record);
  ExpectResumesToTheWhole(out, 2, "cell.json deleted");
  const nlohmann::json after = nlohmann::json::parse(Slurp(record));
  EXPECT_EQ(after["status"], "ok");
  EXPECT_EQ(after["cell"], before["cell"]);
  EXPECT_EQ(Slurp(out / "cells" / Cell(1) / "run" / "metrics.json"), metrics);
}

}  // namespace
