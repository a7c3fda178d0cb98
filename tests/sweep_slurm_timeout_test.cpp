// A cell Slurm kills (label `slurm_slow`: it waits out a 1-minute time limit; see
// slurm_cluster.h): the run over its limit is recorded with Slurm's reason and the
// tail of Slurm's own message, the quick cell beside it is ok, and resubmitting runs
// only the killed cell.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "slurm_cluster.h"

namespace {

namespace fs = std::filesystem;
using trackbed::testing_cli::CliResult;
using trackbed::testing_cli::RunTrackbed;
using trackbed::testing_cli::Slurp;

const fs::path kSource = TRACKBED_SOURCE_DIR;

TEST(SweepSlurmTimeoutTest, ACellSlurmKillsIsReportedAndResubmittedAlone) {
  TRACKBED_NEEDS_SLURM();
  const fs::path dir =
      trackbed::testing_cli::FreshTempDir("trackbed_sweep_slurm_timeout_test_", "limit");
  // The park without the camera for 2 s (a second of wall time), and for 100000 s on a
  // route of 1000 laps (minutes of wall time): the second cannot finish within 1 min.
  const fs::path sweep = dir / "limit.yaml";
  std::ofstream(sweep) << "name: limit\n"
                       << "scenarios: [" << (kSource / "scenes/outdoor.yaml").string() << "]\n"
                       << "seeds: [1]\n"
                       << "set: [\"robot.stereo.enabled=false\", \"drive.laps=1000\"]\n"
                       << "vary:\n"
                       << "  - {key: duration_s, values: [2, 100000]}\n";
  const fs::path out = dir / "sweep";
  const std::string quick = "outdoor__duration_s-2__seed-1";
  const std::string slow = "outdoor__duration_s-100000__seed-1";

  const CliResult r = RunTrackbed("sweep " + sweep.string() + " --out " + out.string() +
                                      " --backend slurm --time-limit 1 --wait",
                                  dir / "io1");
  EXPECT_EQ(r.exit_code, 1) << r.stdout_text << r.stderr_text;  // a cell did not finish
  EXPECT_NE(r.stdout_text.find("limit: 1 ok, 0 failed, 1 timed out"), std::string::npos)
      << r.stdout_text;
  const nlohmann::json killed = nlohmann::json::parse(Slurp(out / "cells" / slow / "cell.json"));
  EXPECT_EQ(killed["status"], "timed_out");
  EXPECT_EQ(killed["reason"], "stopped by Slurm: TIMEOUT (TimeLimit)");
  EXPECT_NE(killed["stderr_tail"].get<std::string>().find("DUE TO TIME LIMIT"), std::string::npos)
      << killed["stderr_tail"];
  EXPECT_FALSE(fs::exists(out / "cells" / slow / "run/metrics.json"));
  const nlohmann::json ok = nlohmann::json::parse(Slurp(out / "cells" / quick / "cell.json"));
  EXPECT_EQ(ok["status"], "ok");
  EXPECT_NE(Slurp(out / "summary.csv").find("stopped by Slurm: TIMEOUT (TimeLimit)"),
            std::string::npos);

  // Resubmitting runs only the killed cell (index 1); the finished one is left alone.
  const std::string ok_before = Slurp(out / "cells" / quick / "cell.json");
  const CliResult again = RunTrackbed(
      "sweep " + sweep.string() + " --out " + out.string() + " --backend slurm --time-limit 1",
      dir / "io2");
  EXPECT_EQ(again.exit_code, 0) << again.stderr_text;
  EXPECT_NE(again.stdout_text.find("submitted 1 cell as Slurm array job "), std::string::npos)
      << again.stdout_text;
  const nlohmann::json jobs = nlohmann::json::parse(Slurp(out / "slurm/jobs.json"));
  ASSERT_EQ(jobs["jobs"].size(), 2u);
  EXPECT_EQ(jobs["jobs"][1]["cells"], nlohmann::json({1}));
  EXPECT_EQ(Slurp(out / "cells" / quick / "cell.json"), ok_before);
  // Not waited for: it would only be killed again.
  const std::string job = jobs["jobs"][1]["job_id"];
  EXPECT_EQ(std::system(("scancel " + job).c_str()), 0);
}

}  // namespace
