// The `trackbed` command line end to end: the shipped scenes, the run-folder
// contract (README.md "Commands", docs/run_folder.md), determinism, and errors on bad input.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;

using trackbed::testing_cli::CliResult;
using Result = CliResult;
using trackbed::testing_cli::Slurp;

fs::path TempDir(const std::string& name) {
  return trackbed::testing_cli::FreshTempDir("trackbed_cli_test_", name);
}

// Runs `trackbed ARGS` from the source directory, capturing both streams.
Result Trackbed(const std::string& args, const std::string& tag) {
  return trackbed::testing_cli::RunTrackbed(args, TempDir("io_" + tag));
}

nlohmann::json Metrics(const fs::path& run) {
  return nlohmann::json::parse(Slurp(run / "metrics.json"));
}

double EncoderError(const nlohmann::json& m) {
  const double d = m["distance_m"], e = m["encoder_distance_m"];
  return std::abs(e - d) / d;
}

TEST(CliTest, CorridorRunWritesTheRunFolderAndEncodersMatchOnTheFloor) {
  const fs::path out = TempDir("corridor");
  const Result r =
      Trackbed("run scenes/corridor.yaml --set robot.stereo.enabled=false --out " + out.string(),
               "corridor");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  for (const char* f : {"scenario.yaml", "ground_truth.tum", "encoders.csv", "slip.csv", "imu.csv",
                        "tracks.csv", "metrics.json"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  EXPECT_EQ(Slurp(out / "encoders.csv").substr(0, 26), "t,left_ticks,right_ticks\n0");
  EXPECT_EQ(Slurp(out / "slip.csv").rfind("t,left_true_mps,right_true_mps,", 0), 0u);
  const nlohmann::json m = Metrics(out);
  EXPECT_EQ(m["status"], "completed");
  EXPECT_EQ(m["stop_reason"], "path finished");
  for (const char* key :
       {"sim_time_s", "wall_time_s", "real_time_factor", "distance_m", "encoder_distance_m"}) {
    EXPECT_TRUE(m.contains(key)) << key;
  }
  EXPECT_NEAR(m["distance_m"].get<double>(), 40.0, 2.0);
  EXPECT_LT(EncoderError(m), 0.01);
  // The resolved scenario reproduces the run.
  const fs::path again = TempDir("corridor_again");
  const Result r2 = Trackbed("run " + (out / "scenario.yaml").string() + " --out " + again.string(),
                             "corridor_again");
  ASSERT_EQ(r2.exit_code, 0) << r2.stderr_text;
  EXPECT_EQ(Slurp(out / "ground_truth.tum"), Slurp(again / "ground_truth.tum"));
}

TEST(CliTest, TheRunFolderCarriesTheBuiltinMaterialsItUsed) {
  const fs::path out = TempDir("materials");
  const Result r = Trackbed(
      "run scenes/calibration/straight_line.yaml --set duration_s=1 --set "
      "scene.terrain.default_material=dry_sand --out " +
          out.string(),
      "materials");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const std::string yaml = Slurp(out / "scenario.yaml");
  EXPECT_NE(yaml.find("- name: dry_sand\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("bekker_kphi:"), std::string::npos);
  EXPECT_EQ(yaml.find("name: hard_floor\n"), std::string::npos);  // not used, not written
}

TEST(CliTest, AStalledRunSaysSoOnTheCommandLineAndInMetrics) {
  const fs::path out = TempDir("stall");
  const Result r = Trackbed(
      "run scenes/calibration/icr_turns.yaml --set duration_s=5 --set "
      "robot.vehicle.motor.max_torque_nm=2 --out " +
          out.string(),
      "stall");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("the robot stalled at t = "), std::string::npos) << r.stderr_text;
  const nlohmann::json m = Metrics(out);
  EXPECT_EQ(m["stop_reason"], "stalled");
  EXPECT_LT(m["sim_time_s"].get<double>(), 5.0);
}

TEST(CliTest, OutdoorEncodersOverEstimateFarMoreThanInTheCorridor) {
  const fs::path corridor = TempDir("cmp_corridor"), outdoor = TempDir("cmp_outdoor");
  // Physics only: the cameras do not change the driving.
  const std::string no_cameras = " --set robot.stereo.enabled=false --out ";
  ASSERT_EQ(Trackbed("run scenes/corridor.yaml" + no_cameras + corridor.string(), "c").exit_code,
            0);
  const Result r = Trackbed("run scenes/outdoor.yaml" + no_cameras + outdoor.string(), "o");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const nlohmann::json mc = Metrics(corridor), mo = Metrics(outdoor);
  EXPECT_EQ(mo["status"], "completed");
  EXPECT_GT(mo["distance_m"].get<double>(), 35.0);
  EXPECT_GT(EncoderError(mo), 0.01);
  EXPECT_GT(EncoderError(mo), 3.0 * EncoderError(mc));
}

TEST(CliTest, SameScenarioAndSeedGiveIdenticalRunFolders) {
  const fs::path a = TempDir("det_a"), b = TempDir("det_b");
  // With the cameras on and images exported: images are part of the run folder.
  const std::string args =
      "run scenes/outdoor.yaml --set duration_s=4 --set outputs.save_images=kitti --seed 5 --out ";
  ASSERT_EQ(Trackbed(args + a.string(), "a").exit_code, 0);
  ASSERT_EQ(Trackbed(args + b.string(), "b").exit_code, 0);
  int compared = 0;
  for (const auto& entry : fs::recursive_directory_iterator(a)) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), a);
    if (rel == "metrics.json") continue;
    EXPECT_EQ(Slurp(entry.path()), Slurp(b / rel)) << rel << " differs";
    ++compared;
  }
  EXPECT_GT(compared, 90);  // 41 stereo pairs, their calibration, times, poses and the logs
  nlohmann::json ma = Metrics(a), mb = Metrics(b);
  for (nlohmann::json* m : {&ma, &mb}) {
    m->erase("wall_time_s");
    m->erase("real_time_factor");
    m->erase("timing");  // wall-clock time per stage
    m->erase("memory");  // peak resident memory depends on the allocator and the machine
  }
  EXPECT_EQ(ma.dump(), mb.dump());
  // Another seed: another (rough) terrain, another trajectory.
  const fs::path c = TempDir("det_c");
  ASSERT_EQ(
      Trackbed("run scenes/outdoor.yaml --set duration_s=15 --seed 6 --out " + c.string(), "c6")
          .exit_code,
      0);
  EXPECT_NE(Slurp(a / "ground_truth.tum"), Slurp(c / "ground_truth.tum"));
}

TEST(CliTest, EstimatorsAreWrittenBesideGroundTruthAndScored) {
  const fs::path out = TempDir("estimators");
  const Result r =
      Trackbed("run scenes/outdoor.yaml --set duration_s=10 --out " + out.string(), "est");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  auto lines = [](const fs::path& p) {
    const std::string text = Slurp(p);
    return std::count(text.begin(), text.end(), '\n');
  };
  const auto truth_lines = lines(out / "ground_truth.tum");
  EXPECT_EQ(truth_lines, 1001);  // 100 Hz over 10 s, both ends
  for (const char* f :
       {"wheel_odometry.tum", "wheel_odometry_noslip.tum", "ekf.tum", "fused.tum"}) {
    EXPECT_EQ(lines(out / f), truth_lines) << f;
  }
  EXPECT_EQ(lines(out / "visual_odometry.tum"), 101);  // one per stereo frame
  EXPECT_EQ(lines(out / "fusion.csv"), 102);           // and a header
  EXPECT_EQ(Slurp(out / "fusion.csv").rfind("t,slip_velocity_mps,features,w,", 0), 0u);
  // slip.csv: true and estimated slip side by side, ten columns on every row.
  std::istringstream slip(Slurp(out / "slip.csv"));
  std::string row;
  std::getline(slip, row);
  EXPECT_NE(row.find("left_est_mps,right_est_mps"), std::string::npos);
  while (std::getline(slip, row)) ASSERT_EQ(std::count(row.begin(), row.end(), ','), 9) << row;
  // vo_covariance.csv: VO's motion and covariance per stereo frame, 30 columns; on a
  // frame with a motion a covariance with positive variances.
  EXPECT_EQ(lines(out / "vo_covariance.csv"), 102);
  std::istringstream covariance(Slurp(out / "vo_covariance.csv"));
  std::getline(covariance, row);
  EXPECT_EQ(row.rfind("t,vo_status,x_m,y_m,z_m,rx_rad,ry_rad,rz_rad,image_noise_px,c00,c01,", 0),
            0u);
  int with_covariance = 0;
  while (std::getline(covariance, row)) {
    ASSERT_EQ(std::count(row.begin(), row.end(), ','), 29) << row;
    if (row.find(",ok,") == std::string::npos) continue;
    std::vector<std::string> f;
    std::istringstream cells(row);
    for (std::string c; std::getline(cells, c, ',');) f.push_back(c);
    ASSERT_EQ(f.size(), 30u) << row;
    // c00, c11, …, c55: the diagonal of the upper triangle, row by row.
    for (int k : {9, 15, 20, 24, 27, 29}) EXPECT_GT(std::stod(f[static_cast<std::size_t>(k)]), 0.0);
    ++with_covariance;
  }
  EXPECT_GT(with_covariance, 80);
  const nlohmann::json m = Metrics(out);
  for (const char* name :
       {"wheel_odometry", "wheel_odometry_noslip", "visual_odometry", "fused", "ekf"}) {
    ASSERT_TRUE(m["estimators"].contains(name)) << name;
    for (const char* key :
         {"ate_rmse_m", "final_error_m", "final_error_pct", "rpe_trans_pct", "ate3d_se3_rmse_m"}) {
      EXPECT_TRUE(m["estimators"][name].contains(key)) << name << "." << key;
    }
  }
  // Four metres of rough ground: every estimator that does not depend on vision
  // alone stays within half a metre of the truth.
  for (const char* name : {"wheel_odometry", "wheel_odometry_noslip", "fused", "ekf"}) {
    EXPECT_LT(m["estimators"][name]["ate_rmse_m"].get<double>(), 0.5) << name;
  }
  EXPECT_GT(m["localization"]["mean_inliers"].get<double>(), 20.0);
  // The paper's figures as PNG plots.
  for (const char* png : {"trajectories.png", "error_histogram.png", "fusion.png"}) {
    const std::string bytes = Slurp(out / png);
    ASSERT_GT(bytes.size(), 1000u) << png;
    EXPECT_EQ(bytes.substr(1, 3), "PNG") << png;
  }
}

TEST(CliTest, CameraBlackoutMidRunFusionLeansOnWheelsAndTheRunCompletes) {
  const fs::path out = TempDir("blackout");
  const Result r = Trackbed(
      "run scenes/outdoor.yaml --set duration_s=20 --set robot.stereo.blackouts_s=[[8,3]] --out " +
          out.string(),
      "blackout");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const nlohmann::json m = Metrics(out);
  EXPECT_EQ(m["status"], "completed");
  EXPECT_EQ(m["localization"]["camera_blackout_frames"].get<int>(), 30);  // 3 s at 10 Hz
  // During the blackout VO reports no features and fusion takes the wheels whole.
  std::istringstream fusion(Slurp(out / "fusion.csv"));
  std::string row;
  std::getline(fusion, row);
  EXPECT_EQ(row,
            "t,slip_velocity_mps,features,w,vo_status,vo_tracked,camera_blackout,w_rule,"
            "vo_dynamics_constrained");
  int blacked = 0, recovered = 0;
  while (std::getline(fusion, row)) {
    std::vector<std::string> f;
    std::istringstream cells(row);
    for (std::string c; std::getline(cells, c, ',');) f.push_back(c);
    ASSERT_EQ(f.size(), 9u) << row;
    const double t = std::stod(f[0]);
    if (f[6] == "1") {
      ++blacked;
      EXPECT_EQ(f[2], "0") << row;
      EXPECT_DOUBLE_EQ(std::stod(f[3]), 1.0) << row;
      EXPECT_NE(f[4], "ok") << row;
    } else if (t > 12.0 && f[4] == "ok") {
      ++recovered;
    }
  }
  EXPECT_EQ(blacked, 30);
  EXPECT_GT(recovered, 70);  // VO is back after the fault
  // No NaN anywhere in the fused trajectory, and it stays near the truth.
  EXPECT_EQ(Slurp(out / "fused.tum").find("nan"), std::string::npos);
  EXPECT_LT(m["estimators"]["fused"]["ate_rmse_m"].get<double>(), 0.2);
}

// An encoder dropout: the left track's count freezes from 6 s to 10 s and the
// motion meanwhile is lost, so the wheels see the robot turn right. VO sees the truth: the
// slip estimate swells, the fusion's wheel weight falls to the rule base's lowest
// terms, and the fused pose follows VO, far nearer the truth than the wheels'.
TEST(CliTest, AnEncoderDropoutFreezesItsCountAndFusionLeansOnVisualOdometry) {
  const fs::path out = TempDir("dropout");
  const Result r = Trackbed(
      "run scenes/outdoor.yaml --set duration_s=14 --set "
      "\"robot.encoders.dropouts_s=[{track: left, start_s: 6, duration_s: 4}]\" --out " +
          out.string(),
      "dropout");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  std::istringstream encoders(Slurp(out / "encoders.csv"));
  std::string row;
  std::getline(encoders, row);
  long long left_at_6 = -1, left_before_10 = -1, right_at_6 = -1, right_before_10 = -1;
  while (std::getline(encoders, row)) {
    double t = 0;
    long long left = 0, right = 0;
    ASSERT_EQ(std::sscanf(row.c_str(), "%lf,%lld,%lld", &t, &left, &right), 3) << row;
    if (std::abs(t - 6.0) < 1e-9) left_at_6 = left, right_at_6 = right;
    if (std::abs(t - 9.99) < 1e-9) left_before_10 = left, right_before_10 = right;
  }
  EXPECT_EQ(left_before_10, left_at_6);           // frozen
  EXPECT_GT(right_before_10 - right_at_6, 1000);  // the right track counts on
  const nlohmann::json m = Metrics(out);
  EXPECT_EQ(m["status"], "completed");
  const double wheels = m["estimators"]["wheel_odometry_noslip"]["ate_rmse_m"].get<double>();
  const double fused = m["estimators"]["fused"]["ate_rmse_m"].get<double>();
  const double vo = m["estimators"]["visual_odometry"]["ate_rmse_m"].get<double>();
  std::printf("dropout: no-slip wheels %.3f m, VO %.3f m, fused %.3f m\n", wheels, vo, fused);
  EXPECT_LT(3.0 * fused, wheels);
  EXPECT_LT(fused, 2.0 * vo + 0.05);
  EXPECT_EQ(Slurp(out / "fused.tum").find("nan"), std::string::npos);
}

// A 0.8 s blackout while the robot drives and turns: VO's own pose coasts at the last
// valid velocity (estimation.vo_coast_time_s, 1 s) over its 8 frames and the one after
// it (nothing to track from a black image), where holding it drops the motion meanwhile.
TEST(CliTest, VisualOdometryCoastsOverAShortBlackout) {
  const auto run = [&](const std::string& name, const std::string& extra) {
    const fs::path out = TempDir(name);
    const Result r = Trackbed(
        "run scenes/outdoor.yaml --set duration_s=12 --set "
        "robot.stereo.blackouts_s=[[8,0.8]] " +
            extra + " --out " + out.string(),
        name);
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    return Metrics(out);
  };
  const nlohmann::json coast = run("coast", "");
  const nlohmann::json hold = run("hold", "--set estimation.vo_coast_time_s=0");
  EXPECT_EQ(coast["localization"]["vo_coasted"].get<int>(), 9);
  EXPECT_EQ(hold["localization"]["vo_coasted"].get<int>(), 0);
  const double coast_m = coast["estimators"]["visual_odometry"]["final_error_m"].get<double>();
  const double hold_m = hold["estimators"]["visual_odometry"]["final_error_m"].get<double>();
  std::printf("VO's final error after a 0.8 s blackout: %.3f m coasting, %.3f m holding\n", coast_m,
              hold_m);
  EXPECT_LT(coast_m, 0.15);  // 0.113 m measured: the turn rate changes meanwhile
  EXPECT_GT(hold_m, 0.3);
  // The fusion takes the wheels over the blackout either way (its later increments differ
  // only through the planar projection of VO's differently tilted pose).
  EXPECT_NEAR(coast["estimators"]["fused"]["ate_rmse_m"].get<double>(),
              hold["estimators"]["fused"]["ate_rmse_m"].get<double>(), 0.001);
}

TEST(CliTest, UnknownKeyFailsWithFileKeyAndReasonOnOneLine) {
  const fs::path dir = TempDir("bad");
  const fs::path bad = dir / "bad.yaml";
  std::ofstream(bad) << "seed: 1\nrobot:\n  vehicle:\n    mass_kgg: 40\n";
  const Result r = Trackbed("run " + bad.string() + " --out " + (dir / "run").string(), "bad");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(std::count(r.stderr_text.begin(), r.stderr_text.end(), '\n'), 1) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find(bad.string()), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("robot.vehicle.mass_kgg"), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(dir / "run" / "metrics.json"));
}

TEST(CliTest, OutOfRangeOverrideAndMissingFileFailClearly) {
  const fs::path dir = TempDir("range");
  Result r = Trackbed(
      "run scenes/corridor.yaml --set robot.vehicle.mass_kg=-3 --out " + (dir / "run").string(),
      "range");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.stderr_text.find("robot.vehicle.mass_kg"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("must be > 0"), std::string::npos) << r.stderr_text;
  EXPECT_FALSE(fs::exists(dir / "run" / "metrics.json"));

  r = Trackbed("run scenes/no_such_scene.yaml --out " + (dir / "run2").string(), "missing");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.stderr_text.find("scenes/no_such_scene.yaml"), std::string::npos) << r.stderr_text;
  EXPECT_EQ(std::count(r.stderr_text.begin(), r.stderr_text.end(), '\n'), 1) << r.stderr_text;
}

TEST(CliTest, FusionRulesFileIsFoundBesideTheScenarioOrNamedInTheError) {
  const fs::path dir = TempDir("rules");
  std::ofstream(dir / "rules.fll")
      << Slurp(fs::path(TRACKBED_SOURCE_DIR) / "estimation/rules/ham2012_fusion.fll");
  const std::string scenario = Slurp(fs::path(TRACKBED_SOURCE_DIR) / "scenes/corridor.yaml");
  std::ofstream(dir / "scene.yaml")
      << scenario << "estimation: {fusion: {rules_file: rules.fll}}\n";
  Result r = Trackbed("run " + (dir / "scene.yaml").string() + " --set duration_s=1 --out " +
                          (dir / "run").string(),
                      "rules_ok");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(Slurp(dir / "run" / "scenario.yaml").find((dir / "rules.fll").string()),
            std::string::npos);
  r = Trackbed("run scenes/corridor.yaml --set estimation.fusion.rules_file=missing.fll --out " +
                   (dir / "run2").string(),
               "rules_missing");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.stderr_text.find("estimation.fusion.rules_file: no such file"), std::string::npos)
      << r.stderr_text;
}

// Writes a TUM trajectory: 20 poses 0.1 s apart on a circle of radius 5 m (not collinear,
// so the SE(3) alignment is unique), each position shifted by (dx, 0, 0).
void WriteCircleTum(const fs::path& path, double dx) {
  std::ofstream out(path);
  for (int k = 0; k < 20; ++k) {
    const double a = 0.1 * k;
    char line[160];
    std::snprintf(line, sizeof(line), "%.3f %.9f %.9f 0 0 0 0 1\n", 0.1 * k, 5.0 * std::cos(a) + dx,
                  5.0 * std::sin(a));
    out << line;
  }
}

// `trackbed eval --json` on an estimate 0.3 m off the ground truth: unaligned, every
// position error is 0.3 m; SE(3)-aligned, none is left. The layout and the 10-digit
// numbers are pinned too, since scripts read the lines as well as the JSON.
TEST(CliTest, EvalJsonGivesTheAteOfAKnownOffset) {
  const fs::path dir = TempDir("eval");
  const fs::path gt = dir / "gt.tum", est = dir / "est.tum";
  WriteCircleTum(gt, 0.0);
  WriteCircleTum(est, 0.3);
  const std::string files = gt.string() + " " + est.string();

  Result r = Trackbed("eval " + files + " --json --align none", "eval_none");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  nlohmann::json j = nlohmann::json::parse(r.stdout_text);
  EXPECT_EQ(j["gt"]["path"], gt.string());
  EXPECT_EQ(j["gt"]["format"], "tum");
  EXPECT_EQ(j["est"]["poses"], 20);
  EXPECT_EQ(j["association"]["pairs"], 20);
  EXPECT_NEAR(j["ate_aligned_m"]["rmse"].get<double>(), 0.3, 1e-6);
  EXPECT_NEAR(j["ate_aligned_m"]["max"].get<double>(), 0.3, 1e-6);
  EXPECT_NEAR(j["ate_rmse_m"].get<double>(), 0.3, 1e-6);
  EXPECT_TRUE(j["kitti"].is_null());  // a 9.5 m path: no 100 m segment
  EXPECT_NE(r.stdout_text.find("\n  \"association\": {\"pairs\": 20, \"by_index\": false, "
                               "\"max_dt_s\": 0.02, \"offset_s\": 0},\n"),
            std::string::npos)
      << r.stdout_text;
  EXPECT_NE(r.stdout_text.find("\"scale\": 1, \"unique\": true, "
                               "\"R\": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], \"t\": [0, 0, 0]},\n"),
            std::string::npos)
      << r.stdout_text;

  r = Trackbed("eval " + files + " --json", "eval_se3");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  j = nlohmann::json::parse(r.stdout_text);
  EXPECT_EQ(j["alignment"]["mode"], "se3");
  EXPECT_LT(j["ate_aligned_m"]["rmse"].get<double>(), 1e-6);
  EXPECT_NEAR(j["alignment"]["t"][0].get<double>(), -0.3, 1e-6);
  EXPECT_NEAR(j["ate_rmse_m"].get<double>(), 0.3, 1e-6);  // unaligned, whatever --align
}

TEST(CliTest, HelpAndMissingArgumentsFollowTheExitContract) {
  EXPECT_EQ(Trackbed("--help", "help").exit_code, 0);
  EXPECT_EQ(Trackbed("run --help", "run_help").exit_code, 0);
  EXPECT_NE(Trackbed("run scenes/corridor.yaml", "no_out").exit_code, 0);
}

TEST(CliTest, AMisspeltSubcommandOrOptionIsAnsweredWithTheClosestValidOne) {
  const Result runn = Trackbed("runn scenes/corridor.yaml", "runn");
  EXPECT_NE(runn.exit_code, 0);
  EXPECT_EQ(runn.stderr_text,
            "trackbed: unknown subcommand 'runn'; did you mean 'run'?\n"
            "Run with --help for more information.\n");
  const Result seed = Trackbed("run scenes/corridor.yaml --out x --seeed 3", "seeed");
  EXPECT_NE(seed.exit_code, 0);
  EXPECT_EQ(seed.stderr_text.substr(0, seed.stderr_text.find('\n')),
            "trackbed run: unknown option '--seeed'; did you mean '--seed'?");
  const Result jobs = Trackbed("sweep x.yaml --out y --jbos=2", "jbos");
  EXPECT_EQ(jobs.stderr_text.substr(0, jobs.stderr_text.find('\n')),
            "trackbed sweep: unknown option '--jbos'; did you mean '--jobs'?");
  // Nothing close: the valid ones.
  const Result far = Trackbed("xyz", "xyz");
  EXPECT_EQ(
      far.stderr_text.substr(0, far.stderr_text.find('\n')),
      "trackbed: unknown subcommand 'xyz' (one of: run eval sweep sweep-cell report vo transfer "
      "image-stats export-mcap)");
  // A negative value is a value, not an option.
  const Result offset = Trackbed("eval a.tum b.tum --t-offset -0.5", "offset");
  EXPECT_EQ(offset.stderr_text.find("unknown"), std::string::npos) << offset.stderr_text;
}

TEST(CliTest, AStationaryRunGivesNoPercentageOfItsZeroPath) {
  // The robot stands still for the corridor's 130 s: the path is jitter (~10⁻¹⁶ m), so
  // every figure per distance is n/a, in the summary and in metrics.json.
  const fs::path out = TempDir("stationary");
  const Result r = Trackbed(
      "run scenes/corridor.yaml --set drive.mode=script --set \"drive.script=[{t_s: 0, "
      "v_mps: 0}]\" --set robot.stereo.enabled=false --out " +
          out.string(),
      "stationary");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_NE(r.stdout_text.find("distance 0.00 m, encoder distance "), std::string::npos);
  EXPECT_NE(r.stdout_text.find(" m (error n/a: path < 1 m); outputs in"), std::string::npos)
      << r.stdout_text;
  for (const char* name : {"ekf", "wheel_odometry", "wheel_odometry_noslip"}) {
    const std::string row = std::string(name) + std::string(22 - std::strlen(name), ' ');
    const std::size_t at = r.stdout_text.find("\n" + row);
    ASSERT_NE(at, std::string::npos) << name << " in\n" << r.stdout_text;
    const std::string line =
        r.stdout_text.substr(at + 1, r.stdout_text.find('\n', at + 1) - at - 1);
    EXPECT_NE(line.find("n/a (< 1 m)   n/a (< 10 m)"), std::string::npos) << line;
  }
  EXPECT_EQ(r.stdout_text.find("ICR expansion"), std::string::npos);  // it never turned
  const nlohmann::json m = Metrics(out);
  EXPECT_LT(m["distance_m"].get<double>(), 1e-6);
  EXPECT_TRUE(m["encoder_distance_error_pct"].is_null());
  for (const auto& [name, e] : m["estimators"].items()) {
    EXPECT_TRUE(e["final_error_pct"].is_null()) << name;
    EXPECT_TRUE(e["rpe_trans_pct"].is_null()) << name;
    EXPECT_LT(e["final_error_m"].get<double>(), 0.01) << name;
  }
  // Means over nothing: no track moved, no camera frame.
  EXPECT_EQ(m["slip"]["left"]["samples"], 0);
  EXPECT_TRUE(m["slip"]["left"]["mean_slip_ratio"].is_null());
  EXPECT_EQ(m["localization"]["vo_frames"], 0);
  EXPECT_TRUE(m["localization"]["mean_inliers"].is_null());
  EXPECT_TRUE(m["localization"]["mean_fusion_w"].is_null());
  EXPECT_GE(m["localization"]["slip_estimate_rmse_mps"].get<double>(), 0.0);  // wheels scored
  EXPECT_TRUE(m["icr_expansion"]["chi"].is_null());
  EXPECT_FALSE(m["icr_expansion"]["identified"].get<bool>());
  EXPECT_EQ(m["icr_expansion"]["reason"],
            "too little turning: 0 window(s) above 0.05 rad/s (fewer than 10)");
}

}  // namespace
