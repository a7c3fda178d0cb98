// The commands users run on real data, end to end: `trackbed eval` on the published
// benchmark trajectories (KITTI 00 with ORB-SLAM2's estimate, TUM fr2/desk, EuRoC V1_02)
// with each of its flags, and `trackbed vo` on the real KITTI 06 excerpt. They need the
// real data (tests/real_data.h): skipped without it, failed under TRACKBED_REQUIRE_DATA=1.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "real_data.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using trackbed::testing_cli::RunTrackbed;

fs::path Trajectories() { return trackbed::testing_data::RealData("trajectories"); }

std::string Quoted(const fs::path& p) { return "'" + p.string() + "'"; }

// A fresh folder for this test's output (ctest runs the tests in parallel).
fs::path TestDir(const std::string& what) {
  return trackbed::testing_cli::FreshTempDir(
      "trackbed_real_data_cli_",
      std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" + what);
}

// `trackbed eval GT EST FLAGS --json`, parsed; the test fails where it does not exit 0.
json Eval(const std::string& gt, const std::string& est, const std::string& flags) {
  const fs::path d = Trajectories();
  const fs::path io = TestDir("eval");
  const auto r =
      RunTrackbed("eval " + Quoted(d / gt) + " " + Quoted(d / est) + " " + flags + " --json", io);
  EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
  return r.exit_code == 0 ? json::parse(r.stdout_text) : json::object();
}

constexpr double kTol = 0.005;  // the published figures' last digit

TEST(EvalRealDataTest, Kitti00OrbSlam2GivesThePublishedFigures) {
  TRACKBED_NEEDS_REAL_DATA(Trajectories());
  const json j = Eval("KITTI_00_gt.txt", "KITTI_00_ORB.txt", "");
  ASSERT_FALSE(j.empty());
  EXPECT_EQ(j["gt"]["format"], "kitti");
  EXPECT_EQ(j["association"]["pairs"], 4541);
  EXPECT_TRUE(j["association"]["by_index"]);
  EXPECT_NEAR(j["kitti"]["t_rel_pct"].get<double>(), 0.700, kTol);
  EXPECT_NEAR(j["kitti"]["r_rel_deg_per_100m"].get<double>(), 0.25, kTol);
  EXPECT_NEAR(j["ate_aligned_m"]["rmse"].get<double>(), 1.303, kTol);
  EXPECT_EQ(j["alignment"]["mode"], "se3");
  // The table (no --json) prints the same figures.
  const auto r = RunTrackbed("eval " + Quoted(Trajectories() / "KITTI_00_gt.txt") + " " +
                                 Quoted(Trajectories() / "KITTI_00_ORB.txt"),
                             TestDir("table"));
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stdout_text.find("KITTI t_rel (100..800 m)                      0.700  %"),
            std::string::npos)
      << r.stdout_text;
  EXPECT_NE(r.stdout_text.find("ATE RMSE (3-D, se3-aligned)                  1.3034  m"),
            std::string::npos);
}

TEST(EvalRealDataTest, FormatFlagsNameTheFormatsAndAWrongOneIsRefused) {
  TRACKBED_NEEDS_REAL_DATA(Trajectories());
  const json forced = Eval("KITTI_00_gt.txt", "KITTI_00_ORB.txt", "--format kitti");
  EXPECT_NEAR(forced["kitti"]["t_rel_pct"].get<double>(), 0.700, kTol);
  const json euroc = Eval("V102_groundtruth.csv", "V102.txt", "--gt-format euroc --est-format tum");
  EXPECT_EQ(euroc["gt"]["format"], "euroc");
  EXPECT_EQ(euroc["est"]["format"], "tum");
  EXPECT_EQ(euroc["association"]["pairs"], 798);
  EXPECT_NEAR(euroc["ate_aligned_m"]["rmse"].get<double>(), 0.0917, 0.001);
  // A KITTI file read as TUM: exit 2, the file, the line and what was expected.
  const auto r = RunTrackbed("eval " + Quoted(Trajectories() / "KITTI_00_gt.txt") + " " +
                                 Quoted(Trajectories() / "KITTI_00_ORB.txt") + " --gt-format tum",
                             TestDir("format"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("KITTI_00_gt.txt:1: expected 8 fields"), std::string::npos)
      << r.stderr_text;
}

TEST(EvalRealDataTest, TimesFilesAssociateByTimeAndGiveTheIndexResult) {
  TRACKBED_NEEDS_REAL_DATA(Trajectories());
  const std::string times = Quoted(Trajectories() / "KITTI_00_gt_times.txt");
  for (const std::string& flags :
       {"--times " + times, "--gt-times " + times + " --est-times " + times}) {
    const json j = Eval("KITTI_00_gt.txt", "KITTI_00_ORB.txt", flags);
    EXPECT_FALSE(j["association"]["by_index"]) << flags;
    EXPECT_EQ(j["association"]["pairs"], 4541) << flags;
    EXPECT_NEAR(j["kitti"]["t_rel_pct"].get<double>(), 0.700, kTol) << flags;
  }
}

TEST(EvalRealDataTest, AlignmentFlagChangesTheAlignmentOnly) {
  TRACKBED_NEEDS_REAL_DATA(Trajectories());
  const json sim3 = Eval("KITTI_00_gt.txt", "KITTI_00_ORB.txt", "--align sim3");
  EXPECT_EQ(sim3["alignment"]["mode"], "sim3");
  EXPECT_NEAR(sim3["alignment"]["scale"].get<double>(), 1.0047, 1e-4);
  EXPECT_LT(sim3["ate_aligned_m"]["rmse"].get<double>(), 1.303);
  const json none = Eval("KITTI_00_gt.txt", "KITTI_00_ORB.txt", "--align none");
  EXPECT_EQ(none["alignment"]["mode"], "none");
  EXPECT_GT(none["ate_aligned_m"]["rmse"].get<double>(), 1.303);
  EXPECT_NEAR(none["kitti"]["t_rel_pct"].get<double>(), 0.700, kTol);  // alignment-free
}

TEST(EvalRealDataTest, MaxDtAndTimeOffsetChangeTheAssociation) {
  TRACKBED_NEEDS_REAL_DATA(Trajectories());
  // evo's own output on this pair with its 0.01 s: 2174 pairs, rmse 0.008119
  // (github.com/MichaelGrupp/evo/issues/8).
  const json evo = Eval("fr2_desk_groundtruth.txt", "fr2_desk_ORB.txt", "--max-dt 0.01");
  EXPECT_EQ(evo["association"]["pairs"], 2174);
  EXPECT_NEAR(evo["ate_aligned_m"]["rmse"].get<double>(), 0.008119, 1e-6);
  const json wide = Eval("fr2_desk_groundtruth.txt", "fr2_desk_ORB.txt", "");
  EXPECT_EQ(wide["association"]["pairs"], 2223);
  // The estimate's clock shifted by 0.2 s: other pairs, and the error of a lag.
  const json late = Eval("fr2_desk_groundtruth.txt", "fr2_desk_ORB.txt", "--t-offset 0.2");
  EXPECT_EQ(late["association"]["offset_s"], 0.2);
  EXPECT_GT(late["ate_aligned_m"]["rmse"].get<double>(), 4 * 0.008119);
}

TEST(EvalRealDataTest, DeltaFlagsSetTheRelativeErrorsSpacing) {
  TRACKBED_NEEDS_REAL_DATA(Trajectories());
  const json frames = Eval("KITTI_00_gt.txt", "KITTI_00_ORB.txt", "--delta 10");
  EXPECT_EQ(frames["rpe"]["delta"], 10);
  EXPECT_EQ(frames["rpe"]["trans_m"]["count"], 454);  // every 10th of 4541 poses, as evo_rpe
  const json metres = Eval("KITTI_00_gt.txt", "KITTI_00_ORB.txt", "--delta 100 --delta-unit m");
  EXPECT_EQ(metres["rpe"]["delta_unit"], "m");
  EXPECT_EQ(metres["rpe"]["trans_m"]["count"], 37);  // 3724 m of path in 100 m steps
}

TEST(VoRealDataTest, Kitti06WritesItsFilesAndEndsWithinItsErrorBeforeTheDisparityOffset) {
  const fs::path kitti = trackbed::testing_data::RealData("kitti06");
  TRACKBED_NEEDS_REAL_DATA(kitti);
  const fs::path out = TestDir("vo");
  const auto r = RunTrackbed("vo " + Quoted(kitti) + " --out " + Quoted(out / "vo"), out / "io");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  // "end-point error: 0.410 m (0.69 % of 59.9 m)": with the disparity offset estimated
  // (0.19 px); 0.96 % with the disparities as measured, which it must not exceed.
  const std::size_t at = r.stdout_text.find("end-point error: ");
  ASSERT_NE(at, std::string::npos) << r.stdout_text;
  std::istringstream line(r.stdout_text.substr(r.stdout_text.find('(', at) + 1));
  double pct = 0.0;
  line >> pct;
  EXPECT_GT(pct, 0.0);
  EXPECT_LE(pct, 0.96);
  EXPECT_NE(r.stdout_text.find("disparity offset: "), std::string::npos);
  EXPECT_NE(r.stdout_text.find("frames: 51 (50 with motion, 0 failed)"), std::string::npos);
  // One pose per frame in each trajectory file, one row per frame in vo_frames.csv.
  const auto lines = [](const fs::path& f) {
    std::ifstream in(f);
    int n = 0;
    for (std::string l; std::getline(in, l);) n += l.empty() || l[0] == '#' ? 0 : 1;
    return n;
  };
  EXPECT_EQ(lines(out / "vo" / "visual_odometry.tum"), 51);
  EXPECT_EQ(lines(out / "vo" / "visual_odometry.kitti.txt"), 51);
  EXPECT_EQ(lines(out / "vo" / "vo_frames.csv"), 52);  // and the header
  // The figures for tools: vo_metrics.json, and one row per frame pair of the 50 in
  // vo_frame_errors.csv whose median is the median printed.
  std::ifstream metrics_file(out / "vo" / "vo_metrics.json");
  const json metrics = json::parse(metrics_file);
  EXPECT_EQ(metrics["frames"], 51);
  EXPECT_EQ(metrics["settings"]["set"], json::array());
  EXPECT_EQ(metrics["options"]["estimate_disparity_offset"], true);
  EXPECT_EQ(metrics["ground_truth"]["frame_to_frame"]["frames"], 50);
  EXPECT_EQ(lines(out / "vo" / "vo_frame_errors.csv"), 51);  // and the header
}

TEST(VoRealDataTest, SetChangesTheOptionsAndIsRecorded) {
  const fs::path kitti = trackbed::testing_data::RealData("kitti06");
  TRACKBED_NEEDS_REAL_DATA(kitti);
  const fs::path out = TestDir("vo_set");
  const auto median = [&](const std::string& sets) {
    const auto r =
        RunTrackbed("vo " + Quoted(kitti) + " --out " + Quoted(out / "vo") + sets, out / "io");
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    std::ifstream in(out / "vo" / "vo_metrics.json");
    const json m = json::parse(in);
    return std::make_pair(
        m["ground_truth"]["frame_to_frame"]["translation_error_pct"]["median"].get<double>(), m);
  };
  const auto [plain, plain_json] = median("");
  const auto [set, set_json] =
      median(" --set ransac.threshold_px=0.5 --set estimate_disparity_offset=false");
  EXPECT_NE(plain, set);
  EXPECT_EQ(set_json["options"]["ransac"]["threshold_px"], 0.5);
  EXPECT_EQ(set_json["options"]["estimate_disparity_offset"], false);
  EXPECT_EQ(set_json["settings"]["set"],
            json::array({"ransac.threshold_px=0.5", "estimate_disparity_offset=false"}));
  // --no-disparity-offset and its key say the same.
  const auto [flag, flag_json] = median(" --no-disparity-offset --set ransac.threshold_px=0.5");
  EXPECT_EQ(flag, set);
  EXPECT_EQ(flag_json["options"], set_json["options"]);
}

}  // namespace
