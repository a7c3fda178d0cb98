// `trackbed transfer` on constructed outcome tables whose figures are known, its errors,
// and `trackbed vo`'s --set and --config errors (apps/transfer_command.h,
// apps/vo_command.h; docs/transfer.md).
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using trackbed::testing_cli::RunTrackbed;

fs::path TestDir(const std::string& what) {
  return trackbed::testing_cli::FreshTempDir(
      "trackbed_transfer_cli_",
      std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" + what);
}

std::string Quoted(const fs::path& p) { return "'" + p.string() + "'"; }

// An outcome table: configuration k has 20 frames of value outcome[k] + a ripple under
// 0.05 that never reorders them.
fs::path WriteTable(const fs::path& path, const std::vector<std::string>& names,
                    const std::vector<double>& outcome) {
  std::ofstream out(path);
  out << "config,sequence,frame,translation_error_pct\n";
  for (std::size_t k = 0; k < names.size(); ++k) {
    for (int f = 0; f < 20; ++f) {
      out << names[k] << ",log," << f << "," << outcome[k] + 0.01 * ((f * 7) % 5) << "\n";
    }
  }
  return path;
}

const std::vector<std::string> kNames = {"budget_4", "default", "lk_9", "ransac_1"};

json RunTransfer(const fs::path& real, const fs::path& sim, const fs::path& dir) {
  const auto r = RunTrackbed("transfer --real " + Quoted(real) + " --sim " + Quoted(sim) +
                                 " --out " + Quoted(dir / "out") + " --resamples 200",
                             dir / "io");
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stdout_text.find("Spearman rho"), std::string::npos) << r.stdout_text;
  std::ifstream in(dir / "out" / "transfer.json");
  return in ? json::parse(in) : json::object();
}

TEST(TransferCliTest, IdenticalReversedAndOneSwapGiveTheirKnownFigures) {
  const fs::path d = TestDir("tables");
  const fs::path real = WriteTable(d / "real.csv", kNames, {1, 2, 3, 4});
  const json same = RunTransfer(real, real, d / "same");
  EXPECT_DOUBLE_EQ(same["all"]["spearman_rho"]["value"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(same["all"]["pearson_r"]["value"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(same["all"]["mmrv"]["value"].get<double>(), 0.0);
  EXPECT_TRUE(fs::exists(d / "same" / "out" / "transfer.png"));
  EXPECT_TRUE(fs::exists(d / "same" / "out" / "transfer_values.png"));
  // Each configuration's outcomes and ranks (1 = the lowest error), by name.
  std::ifstream outcomes(d / "same" / "out" / "outcomes.csv");
  std::string header, first;
  std::getline(outcomes, header);
  std::getline(outcomes, first);
  EXPECT_EQ(header, "config,real,sim,real_rank,sim_rank,near_best");
  // The median of 1 + 0.01 · (0, 2, 4, 1, 3) four times over.
  EXPECT_EQ(first, "budget_4,1.02,1.02,1,1,1");
  EXPECT_TRUE(fs::exists(d / "same" / "out" / "real_outcomes.csv"));

  const json reversed =
      RunTransfer(real, WriteTable(d / "reversed.csv", kNames, {4, 3, 2, 1}), d / "reversed");
  EXPECT_DOUBLE_EQ(reversed["all"]["spearman_rho"]["value"].get<double>(), -1.0);
  EXPECT_NEAR(reversed["all"]["mmrv"]["value"].get<double>(), 5.0 / 6.0, 1e-12);

  // "default" and "lk_9" swapped: rho = r = 0.8, MMRV = 1/6 (rank_correlation_test).
  const json swapped =
      RunTransfer(real, WriteTable(d / "swapped.csv", kNames, {1, 3, 2, 4}), d / "swapped");
  EXPECT_NEAR(swapped["all"]["spearman_rho"]["value"].get<double>(), 0.8, 1e-12);
  EXPECT_NEAR(swapped["all"]["pearson_r"]["value"].get<double>(), 0.8, 1e-12);
  EXPECT_NEAR(swapped["all"]["mmrv"]["value"].get<double>(), 1.0 / 6.0, 1e-12);
  // Near the best (within 1.5 × 1.0 on real): budget_4 alone, too few to rank.
  EXPECT_EQ(swapped["near_best"]["configurations"], json::array({"budget_4"}));
  EXPECT_TRUE(swapped["near_best"]["spearman_rho"]["value"].is_null());
}

TEST(TransferCliTest, AConfigurationInOneTableOnlyIsNamed) {
  const fs::path d = TestDir("missing");
  const fs::path real = WriteTable(d / "real.csv", kNames, {1, 2, 3, 4});
  const fs::path sim = WriteTable(d / "sim.csv", {"budget_4", "default", "lk_9"}, {1, 2, 3});
  const auto r = RunTrackbed(
      "transfer --real " + Quoted(real) + " --sim " + Quoted(sim) + " --out " + Quoted(d / "out"),
      d / "io");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.stderr_text,
            "trackbed transfer: configuration 'ransac_1' has real outcomes but no simulated "
            "ones\n");
}

TEST(TransferCliTest, ATableWithoutTheMetricOrWithABadValueIsNamed) {
  const fs::path d = TestDir("bad");
  const fs::path real = WriteTable(d / "real.csv", kNames, {1, 2, 3, 4});
  auto r = RunTrackbed("transfer --real " + Quoted(real) + " --sim " + Quoted(real) +
                           " --metric rotation_error_deg --out " + Quoted(d / "out"),
                       d / "io");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.stderr_text, "trackbed transfer: " + (d / "real.csv").string() +
                               ":1: no 'rotation_error_deg' column (the metric)\n");
  {
    std::ofstream bad(d / "bad.csv");
    bad << "config,translation_error_pct\nbudget_4,1\ndefault,abc\n";
  }
  r = RunTrackbed("transfer --real " + Quoted(d / "bad.csv") + " --sim " + Quoted(real) +
                      " --out " + Quoted(d / "out"),
                  d / "io");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.stderr_text, "trackbed transfer: " + (d / "bad.csv").string() +
                               ":3: translation_error_pct: expected a finite number, got 'abc'\n");
}

TEST(TransferCliTest, AFolderWithoutVoOutputsIsNamed) {
  const fs::path d = TestDir("folder");
  fs::create_directories(d / "sim" / "default" / "seed1");
  const fs::path real = WriteTable(d / "real.csv", kNames, {1, 2, 3, 4});
  const auto r = RunTrackbed("transfer --real " + Quoted(real) + " --sim " + Quoted(d / "sim") +
                                 " --out " + Quoted(d / "out"),
                             d / "io");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find((d / "sim" / "default").string() + ": no vo_frame_errors.csv"),
            std::string::npos)
      << r.stderr_text;
}

TEST(TransferCliTest, ASweepFolderReadsItsGroupsAsConfigurations) {
  // A sweep folder's summary.csv (only the columns read here, a quoted reason with a
  // comma as `trackbed sweep` writes one): groups a–d, seeds 1–2, the sweep's ATE.
  const fs::path d = TestDir("sweep");
  fs::create_directories(d / "sweep");
  std::ofstream(d / "sweep" / "cells.json") << "{}\n";
  {
    std::ofstream summary(d / "sweep" / "summary.csv");
    summary << "index,cell,group,seed,cell_status,cell_reason,estimators_vo_ate_rmse_m\n";
    const double ate[4][2] = {{0.1, 0.12}, {0.2, 0.22}, {0.3, 0.28}, {0.4, 0.44}};
    for (int g = 0; g < 4; ++g) {
      for (int seed = 1; seed <= 2; ++seed) {
        summary << 2 * g + seed - 1 << ",g" << g << "__seed-" << seed << ",g" << g << "," << seed
                << ",ok,\"a reason, quoted\"," << ate[g][seed - 1] << "\n";
      }
    }
  }
  {
    std::ofstream real(d / "real.csv");
    real << "config,estimators_vo_ate_rmse_m\ng0,0.5\ng1,0.7\ng2,0.6\ng3,0.9\n";
  }
  const auto r = RunTrackbed("transfer --real " + Quoted(d / "real.csv") + " --sim " +
                                 Quoted(d / "sweep") + " --metric estimators_vo_ate_rmse_m" +
                                 " --out " + Quoted(d / "out") + " --resamples 200",
                             d / "io");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  std::ifstream in(d / "out" / "transfer.json");
  const json j = json::parse(in);
  // Simulated means 0.11, 0.21, 0.29, 0.42 against real 0.5, 0.7, 0.6, 0.9: g1 and g2
  // swapped, rho 0.8; MMRV (0.1/0.4 + 0.1/0.4) / 4 = 0.125.
  EXPECT_NEAR(j["all"]["spearman_rho"]["value"].get<double>(), 0.8, 1e-12);
  EXPECT_NEAR(j["all"]["mmrv"]["value"].get<double>(), 0.125, 1e-12);
  EXPECT_FALSE(j["ceiling"]["sim_split_half"]["available"].get<bool>());  // no frames
  // A cell that did not finish is named, with its group.
  std::ofstream(d / "sweep" / "summary.csv", std::ios::app) << "8,g4__seed-1,g4,1,timed_out,,\n";
  const auto bad =
      RunTrackbed("transfer --real " + Quoted(d / "real.csv") + " --sim " + Quoted(d / "sweep") +
                      " --metric estimators_vo_ate_rmse_m" + " --out " + Quoted(d / "out"),
                  d / "io");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.stderr_text, "trackbed transfer: " + (d / "sweep" / "summary.csv").string() +
                                 ":10: a cell of 'g4' did not finish (timed_out): resume the "
                                 "sweep, or leave its configuration out\n");
}

TEST(VoSetCliTest, AnUnknownKeyIsRejectedWithTheKeyNamed) {
  const fs::path d = TestDir("vo");
  // The options are checked before any image is read: an empty folder will do.
  fs::create_directories(d / "sequence");
  auto r = RunTrackbed("vo " + Quoted(d / "sequence") + " --out " + Quoted(d / "out") +
                           " --set tracker.window_px=21 --set tracker.windw_px=3",
                       d / "io");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.stderr_text,
            "trackbed vo: --set tracker.windw_px=3: tracker.windw_px: unknown key (allowed: "
            "window_px, pyramid_levels, max_iterations, epsilon_px, min_eigenvalue, "
            "max_forward_backward_px, border_px)\n");
  EXPECT_FALSE(fs::exists(d / "out"));
  r = RunTrackbed("vo " + Quoted(d / "sequence") + " --out " + Quoted(d / "out") +
                      " --set ransac.threshold_px=-1",
                  d / "io");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("ransac.threshold_px: must be > 0"), std::string::npos)
      << r.stderr_text;
  {
    std::ofstream config(d / "vo.yaml");
    config << "tracker: {window_px: 21}\nbucket_cols: 6\n";
  }
  r = RunTrackbed("vo " + Quoted(d / "sequence") + " --out " + Quoted(d / "out") + " --config " +
                      Quoted(d / "vo.yaml"),
                  d / "io");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find((d / "vo.yaml").string() + ": bucket_cols: unknown key"),
            std::string::npos)
      << r.stderr_text;
}

}  // namespace
