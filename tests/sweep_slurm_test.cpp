// `trackbed sweep --backend slurm` against a real Slurm cluster (label `slurm`; see
// slurm_cluster.h): a sweep of 9 cells submitted as one array job gives the local
// backend's results, and resubmitting a finished sweep submits nothing. The cells are
// the paper's kinematic navigation scene on random fields: well under a second each.
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
using trackbed::testing_cli::DeterministicColumns;
using trackbed::testing_cli::RunTrackbed;
using trackbed::testing_cli::Slurp;

const fs::path kSource = TRACKBED_SOURCE_DIR;

// 3 navigation methods x 3 random fields.
fs::path WriteSweep(const fs::path& dir) {
  const fs::path file = dir / "fields.yaml";
  std::ofstream(file) << "name: fields\n"
                      << "scenarios: [" << (kSource / "scenes/nav_paper_left.yaml").string()
                      << "]\n"
                      << "seeds: [1]\n"
                      << "set: [\"navigation.field=random\", \"navigation.obstacles=[]\"]\n"
                      << "vary:\n"
                      << "  - {key: navigation.method, values: [gauss_newton_subgoal, "
                         "potential_field, dwa]}\n"
                      << "  - {key: navigation.field_seed, range: {from: 0, to: 2}, "
                         "replicate: true}\n"
                      << "timeout_s: 120\n";
  return file;
}

TEST(SweepSlurmTest, AnArrayJobGivesTheLocalBackendsResults) {
  TRACKBED_NEEDS_SLURM();
  const fs::path dir = trackbed::testing_cli::FreshTempDir("trackbed_sweep_slurm_test_", "array");
  const fs::path sweep = WriteSweep(dir);
  const fs::path local = dir / "local", slurm = dir / "slurm";

  const CliResult l = RunTrackbed(
      "sweep " + sweep.string() + " --out " + local.string() + " --jobs 2", dir / "io1");
  ASSERT_EQ(l.exit_code, 0) << l.stderr_text;

  const CliResult s = RunTrackbed("sweep " + sweep.string() + " --out " + slurm.string() +
                                      " --backend slurm --max-parallel 2 --wait",
                                  dir / "io2");
  ASSERT_EQ(s.exit_code, 0) << s.stdout_text << s.stderr_text;
  EXPECT_NE(s.stdout_text.find("submitted 9 cells as Slurm array job "), std::string::npos)
      << s.stdout_text;
  EXPECT_NE(s.stdout_text.find("fields: 9 ok, 0 failed, 0 timed out"), std::string::npos)
      << s.stdout_text;

  // One array job, task i running cell i; every cell ran in it.
  const nlohmann::json jobs = nlohmann::json::parse(Slurp(slurm / "slurm/jobs.json"));
  ASSERT_EQ(jobs["jobs"].size(), 1u);
  const std::string job = jobs["jobs"][0]["job_id"];
  EXPECT_EQ(jobs["jobs"][0]["cells"], nlohmann::json({0, 1, 2, 3, 4, 5, 6, 7, 8}));
  for (const auto& entry : fs::directory_iterator(slurm / "cells")) {
    const nlohmann::json cell = nlohmann::json::parse(Slurp(entry.path() / "cell.json"));
    EXPECT_EQ(cell["status"], "ok") << entry.path();
    EXPECT_EQ(cell["slurm_job"], job + "_" + std::to_string(cell["index"].get<int>()));
  }

  // The same results as the local backend: every column but the machine-dependent ones,
  // and the report.
  EXPECT_EQ(DeterministicColumns(slurm / "summary.csv"),
            DeterministicColumns(local / "summary.csv"));
  EXPECT_EQ(Slurp(slurm / "report.md"), Slurp(local / "report.md"));

  // Resubmitting a finished sweep submits nothing.
  const CliResult again = RunTrackbed(
      "sweep " + sweep.string() + " --out " + slurm.string() + " --backend slurm", dir / "io3");
  EXPECT_EQ(again.exit_code, 0) << again.stderr_text;
  EXPECT_NE(again.stderr_text.find("9 cells, 9 finished already"), std::string::npos)
      << again.stderr_text;
  EXPECT_EQ(again.stdout_text.find("submitted"), std::string::npos) << again.stdout_text;
}

}  // namespace
