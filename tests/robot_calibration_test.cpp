// The robot as built and the software as calibrated (docs/calibration.md): the plant
// runs the robot as built, the software gets only the given calibration files, the
// wheel odometry's radii come from the straight calibration run, and the camera's
// rectification from its given calibration.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "trackbed/common/robot_calibration.h"
#include "trackbed/common/se3.h"
#include "trackbed/estimation/imu_correction.h"
#include "trackbed/perception/stereo_rectifier.h"
#include "trackbed/robot/as_built.h"
#include "trackbed/robot/imu.h"
#include "trackbed/robot/imu_parts.h"
#include "trackbed/runner/closed_loop.h"
#include "trackbed/runner/wheel_calibration_run.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {
namespace {

namespace fs = std::filesystem;

const std::string kSource = TRACKBED_SOURCE_DIR;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("trackbed_robot_calibration_test_" + name);
  fs::remove_all(dir);
  return dir;
}

nlohmann::json ReadJson(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

// A given file's values, without where they came from.
nlohmann::json Values(const fs::path& file) {
  nlohmann::json j = ReadJson(file);
  j.erase("source");
  return j;
}

// Every as-built spread switched on (the vehicle's and the cameras' are not in the
// typical profile, which has no published values for them).
const std::vector<std::string> kAsBuiltSpreads = {
    "robot.imperfections.sprocket_radius_rel_std=0.01",
    "robot.imperfections.track_gauge_rel_std=0.01",
    "robot.imperfections.focal_length_rel_std=0.005",
    "robot.imperfections.principal_point_std_px=2",
    "robot.imperfections.stereo_rotation_std_mrad=[2, 2, 2]",
    "robot.imperfections.camera_mount_std_deg=0.5"};

// `file` (in scenes/) with the as-built spreads and `extra` set.
scenario::Scenario Load(const std::string& file, const std::vector<std::string>& extra) {
  std::vector<std::string> overrides = kAsBuiltSpreads;
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  std::vector<scenario::Override> parsed;
  for (const std::string& o : overrides) parsed.push_back(scenario::ParseOverride(o));
  return scenario::LoadScenario(kSource + "/scenes/" + file, parsed);
}

// The corridor for two seconds with the camera and every as-built spread.
scenario::Scenario ShortCorridor(std::vector<std::string> extra) {
  extra.insert(extra.begin(), "duration_s=2");
  return Load("corridor.yaml", extra);
}

RunMetrics RunInto(const scenario::Scenario& s, const fs::path& dir) {
  ClosedLoopOptions options;
  options.dir = dir;
  return ClosedLoop(s, std::move(options)).Run();
}

TEST(RobotCalibrationTest, TheSoftwareSeesTheGivenFilesWhateverTheRobotAsBuilt) {
  // A first run's given calibration becomes a user's calibration folder.
  const fs::path first = FreshDir("first"), given = FreshDir("given");
  ASSERT_TRUE(RunInto(ShortCorridor({"robot.as_built_seed=11"}), first).completed);
  fs::create_directories(given);
  for (const char* f :
       {calibration::kStereoFile, calibration::kImuFile, calibration::kVehicleFile}) {
    fs::copy_file(first / f, given / f);
  }
  // Two robots as built, the same given folder.
  const fs::path a = FreshDir("a"), b = FreshDir("b");
  const std::string dir = "robot.calibration_dir=" + given.string();
  ASSERT_TRUE(RunInto(ShortCorridor({"robot.as_built_seed=21", dir}), a).completed);
  ASSERT_TRUE(RunInto(ShortCorridor({"robot.as_built_seed=22", dir}), b).completed);
  for (const char* f :
       {calibration::kStereoFile, calibration::kImuFile, calibration::kVehicleFile}) {
    SCOPED_TRACE(f);
    EXPECT_EQ(Values(a / f), Values(given / f));
    EXPECT_EQ(Values(b / f), Values(given / f));
  }
  EXPECT_NE(ReadJson(a / "vehicle_calibration.json")["source"].get<std::string>().find("folder"),
            std::string::npos);
  // The plants differ in every part.
  const nlohmann::json ta = ReadJson(a / calibration::kGroundTruthFile);
  const nlohmann::json tb = ReadJson(b / calibration::kGroundTruthFile);
  for (const char* part : {"stereo", "imu", "vehicle"}) {
    SCOPED_TRACE(part);
    EXPECT_NE(ta[part], tb[part]);
  }
  EXPECT_NE(ta["vehicle"]["sprocket_radius_left_m"], tb["vehicle"]["sprocket_radius_left_m"]);
  EXPECT_NE(ta["stereo"]["fx"], tb["stereo"]["fx"]);
  EXPECT_NE(ta["imu"]["gyro_axes"], tb["imu"]["gyro_axes"]);
}

TEST(RobotCalibrationTest, WheelRadiiFollowTheCalibrationRunNotTheDesign) {
  // Tracks 3 % off the design's radius, each its own way.
  const scenario::Scenario s =
      ShortCorridor({"robot.imperfections.sprocket_radius_rel_std=0.03", "robot.as_built_seed=5"});
  const RobotBuild robot = BuildRunRobot(s);
  const calibration::VehicleCalibration& truth = robot.truth.vehicle;
  const calibration::VehicleCalibration& given = robot.given.vehicle;
  const double design = s.robot.vehicle.sprocket_radius_m;
  ASSERT_GT(std::abs(truth.sprocket_radius_left_m / design - 1.0), 0.005);
  ASSERT_GT(std::abs(truth.sprocket_radius_right_m / truth.sprocket_radius_left_m - 1.0), 0.005);
  // On the hard floor the run measures each track's radius to 0.1 %.
  EXPECT_NEAR(given.sprocket_radius_left_m / truth.sprocket_radius_left_m, 1.0, 1e-3);
  EXPECT_NEAR(given.sprocket_radius_right_m / truth.sprocket_radius_right_m, 1.0, 1e-3);
  EXPECT_EQ(*given.icr_expansion, s.estimation.icr_expansion);

  // The user repeats it with scenes/calibration/straight_line.yaml and the robot's keys:
  // the same fit, to the bit.
  const scenario::Scenario straight =
      Load("calibration/straight_line.yaml",
           {"robot.imperfections.sprocket_radius_rel_std=0.03", "robot.as_built_seed=5"});
  StraightRunFit fit(s.robot.encoders.ticks_per_rev, s.robot.vehicle.track_gauge_m,
                     s.estimation.icr_expansion);
  RunObservers observers;
  observers.on_sample = [&fit](const RunSample& x) { fit.Add(x); };
  ASSERT_TRUE(RunClosedLoop(straight, observers).completed);
  EXPECT_EQ(fit.Result().sprocket_radius_left_m, given.sprocket_radius_left_m);
  EXPECT_EQ(fit.Result().sprocket_radius_right_m, given.sprocket_radius_right_m);

  // Without the calibration run the software is given the truth.
  scenario::Scenario truth_given = s;
  truth_given.robot.imperfections.wheel_calibration = robot::WheelCalibration::kTruth;
  const RobotBuild r2 = BuildRunRobot(truth_given);
  EXPECT_EQ(r2.given.vehicle.sprocket_radius_left_m, truth.sprocket_radius_left_m);
}

TEST(RobotCalibrationTest, IdealGivesTheDesignAndTypicalDrawsAroundIt) {
  scenario::Scenario s = ShortCorridor({"robot.realism=ideal"});
  s.robot.imperfections = robot::Imperfections{};
  const RobotBuild ideal = BuildRunRobot(s);
  EXPECT_EQ(nlohmann::json::parse(calibration::GroundTruthCalibrationJson(ideal.truth)),
            nlohmann::json::parse(calibration::GroundTruthCalibrationJson(ideal.design)));
  EXPECT_TRUE(ideal.given.stereo->IsRectified());
  EXPECT_TRUE(ideal.given.imu.IsIdentity());
  s.robot.realism = robot::Realism::kTypical;
  const RobotBuild typical = BuildRunRobot(s);
  EXPECT_FALSE(typical.given.stereo->IsRectified());
  EXPECT_FALSE(typical.truth.imu.IsIdentity());
  EXPECT_TRUE(typical.given.imu.IsIdentity());  // the software assumes the datasheet's IMU
  // One effect off leaves the others' draws as they were.
  scenario::Scenario no_imu = s;
  no_imu.robot.imperfections.gyro_scale_std = 0.0;
  const RobotBuild b = BuildRunRobot(no_imu);
  EXPECT_EQ(b.given.stereo->T_body_right.matrix(), typical.given.stereo->T_body_right.matrix());
  EXPECT_EQ(b.truth.imu.accel_axes, typical.truth.imu.accel_axes);
  EXPECT_NE(b.truth.imu.gyro_axes, typical.truth.imu.gyro_axes);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(b.truth.imu.gyro_axes(i, i), 1.0);
}

// The software's correction inverts the plant's IMU model: with the true calibration
// given, a noiseless reading of the IMU as built gives back the body's rate, where the
// datasheet's perfect IMU (what typical and harsh give) is off by the as-built error.
TEST(RobotCalibrationTest, TheImuCorrectionInvertsTheImuAsBuilt) {
  robot::Imperfections big;
  big.gyro_scale_std = big.accel_scale_std = 0.03;
  big.gyro_misalignment_std_deg = big.accel_misalignment_std_deg = 1.0;
  big.gyro_g_sensitivity_std_dps_per_g = 0.1;
  big.imu_mount_std_deg = 1.0;
  const calibration::ImuCalibration truth =
      robot::DrawAsBuilt({}, big.Resolve(robot::Realism::kIdeal), 9).imu;
  robot::ImuOptions quiet = robot::WithImuPartResolved({}, robot::Realism::kIdeal);
  quiet.gyro_noise_density = quiet.gyro_bias_random_walk = 0.0;
  quiet.accel_noise_density = quiet.accel_bias_random_walk = 0.0;
  quiet.gyro_initial_bias_std = quiet.accel_initial_bias_std = 0.0;
  robot::Imu imu(quiet, 9.81, 1, &truth);
  const Eigen::Matrix3d R_world_body = geometry::ExpSO3(Eigen::Vector3d(0.1, -0.2, 0.7));
  const Eigen::Vector3d omega_world(0.05, -0.02, 0.6), accel_world(0.3, 0.1, 0.0);
  const robot::ImuSample s = imu.Sample(0.005, R_world_body, omega_world, accel_world);
  const Eigen::Vector3d body_rate = R_world_body.transpose() * omega_world;
  const estimation::ImuCorrection given_truth(truth);
  EXPECT_FALSE(given_truth.identity());
  EXPECT_LT((given_truth.BodyRate(s.gyro_radps, s.accel_mps2) - body_rate).norm(), 1e-12);
  const estimation::ImuCorrection datasheet{calibration::ImuCalibration{}};
  EXPECT_TRUE(datasheet.identity());
  EXPECT_GT((datasheet.BodyRate(s.gyro_radps, s.accel_mps2) - body_rate).norm(), 1e-3);
}

// An 8-bit image, grey (kBackground) but for a Gaussian spot (σ 3 px) centred at `uv`.
// On grey, the undershoot a bicubic resampling rings around the spot is kept rather
// than clipped at 0; a spot several pixels wide keeps the centroid below within a few
// hundredths of a pixel whatever the resampling's sub-pixel phase.
constexpr double kBackground = 50.0;
cv::Mat Spot(int width, int height, const Eigen::Vector2d& uv) {
  cv::Mat image(height, width, CV_8UC1, cv::Scalar(kBackground));
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      const double r2 = (u - uv.x()) * (u - uv.x()) + (v - uv.y()) * (v - uv.y());
      if (r2 < 400.0)
        image.at<unsigned char>(v, u) = cv::saturate_cast<unsigned char>(
            kBackground + 200.0 * std::exp(-r2 / (2.0 * 3.0 * 3.0)));
    }
  }
  return image;
}

// The centre of an image's intensity above the background within 16 px of its
// brightest pixel (the rectified view's edges, which resampling darkens, left out).
Eigen::Vector2d Centroid(const cv::Mat& image) {
  cv::Point peak;
  cv::minMaxLoc(image, nullptr, nullptr, nullptr, &peak);
  double sum = 0.0, su = 0.0, sv = 0.0;
  for (int v = std::max(peak.y - 16, 0); v <= std::min(peak.y + 16, image.rows - 1); ++v) {
    for (int u = std::max(peak.x - 16, 0); u <= std::min(peak.x + 16, image.cols - 1); ++u) {
      const double w = image.at<unsigned char>(v, u) - kBackground;
      sum += w, su += w * u, sv += w * v;
    }
  }
  return {su / sum, sv / sum};
}

TEST(RobotCalibrationTest, RectificationRealignsAPairTurnedAsCalibrated) {
  // A pair whose right camera is turned by about 5 mrad about each axis, known exactly:
  // a spot seen by both raw cameras lands, after rectification, on the same row in
  // both images and at the disparity of its depth.
  robot::Imperfections turn;
  turn.stereo_rotation_std_mrad = Eigen::Vector3d(5, 5, 5);
  robot::StereoRigOptions o;
  o.enabled = true;
  const calibration::RobotCalibration design = robot::DesignCalibration({}, o);
  const calibration::StereoCalibration pair =
      *robot::DrawAsBuilt(design, turn.Resolve(robot::Realism::kIdeal), 3).stereo;
  ASSERT_FALSE(pair.IsRectified());
  const perception::StereoRectifier rectifier(pair);
  ASSERT_FALSE(rectifier.identity());
  const Eigen::Isometry3d T_rect_left = rectifier.T_body_left().inverse() * pair.T_body_left;
  const Eigen::Isometry3d T_right_left = pair.T_left_right().inverse();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.3, 0.2, 2.0), Eigen::Vector3d(-1, 0.5, 6.0),
                                   Eigen::Vector3d(1.5, -0.4, 15.0)}) {
    SCOPED_TRACE(p.transpose());
    const cv::Mat left = Spot(pair.width_px, pair.height_px, pair.LeftCamera().Project(p));
    const cv::Mat right =
        Spot(pair.width_px, pair.height_px, pair.RightCamera().Project(T_right_left * p));
    cv::Mat left_rect, right_rect;
    rectifier.Rectify(left, right, &left_rect, &right_rect);
    const Eigen::Vector2d l = Centroid(left_rect), r = Centroid(right_rect);
    EXPECT_NEAR(l.y(), r.y(), 0.05);  // rows agree
    const Eigen::Vector3d expected = rectifier.camera().Project(T_rect_left * p);
    EXPECT_NEAR(l.x(), expected.x(), 0.05);
    EXPECT_NEAR(r.x(), expected.z(), 0.05);
    // Without rectification the rows disagree by pixels.
    const Eigen::Vector2d l_raw = Centroid(left), r_raw = Centroid(right);
    EXPECT_GT(std::abs(l_raw.y() - r_raw.y()) +
                  std::abs((l_raw.x() - r_raw.x()) - (expected.x() - expected.z())),
              1.0);
  }
}

}  // namespace
}  // namespace trackbed::runner
