// The scenario's `estimation` section against the localization stack it configures:
// every key reaches the options the runner builds, the fields the robot's given
// calibration decides come from it, and the presets hold the tracked robot's and
// KITTI's car's values.
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scenario_key_walk.h"
#include "trackbed/common/archive.h"
#include "trackbed/estimation/localization.h"
#include "trackbed/estimation/stereo_visual_odometry.h"
#include "trackbed/runner/localization_options.h"
#include "trackbed/scenario/key_aliases.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed {
namespace {

// The smallest valid scenario: a path drive needs its waypoints.
constexpr char kMinimal[] = "drive:\n  waypoints: [[0, 0], [5, 0]]\n";

// A given calibration as a run has one: the wheels' geometry, no χ.
calibration::RobotCalibration GivenCalibration() {
  calibration::RobotCalibration given;
  given.vehicle.sprocket_radius_left_m = 0.101;
  given.vehicle.sprocket_radius_right_m = 0.099;
  given.vehicle.track_gauge_m = 0.52;
  return given;
}

// The scenario with `key` set to `value` through a --set override, or none when the
// value is not valid for the key.
std::optional<scenario::Scenario> WithOverride(const std::string& key, const std::string& value) {
  try {
    return scenario::ParseScenario(kMinimal, "walk.yaml", {{key, value}});
  } catch (const scenario::ScenarioError&) {
    return std::nullopt;
  }
}

// The value the options the runner builds from `s` hold for scenario key `key`, as
// written text: the localization options' own keys (the key without `estimation.`)
// and the two keys of the section that are not theirs.
std::string BuiltValue(const scenario::Scenario& s, const std::string& key) {
  const estimation::LocalizationOptions built =
      runner::LocalizationOptionsOf(s, GivenCalibration());
  if (key == "estimation.enabled") return s.estimation.enabled ? "true" : "false";
  if (key == "estimation.icr_expansion") return archive::FormatDouble(built.wheel.icr_expansion);
  const archive::Node written = archive::Write(built);
  const archive::Node* node =
      key_walk::NodeAt(written, key.substr(std::string("estimation.").size()));
  return node && node->IsScalar() ? node->text() : "<not in the built options>";
}

// Every scalar key of the default scenario's `estimation` section.
std::vector<key_walk::ScalarKey> EstimationKeys() {
  return key_walk::ScalarKeysUnder(archive::Write(scenario::Scenario{}), "estimation");
}

TEST(EstimationOptionsTest, WalkCoversTheWholeStack) {
  std::set<std::string> paths;
  for (const key_walk::ScalarKey& k : EstimationKeys()) paths.insert(k.path);
  for (const char* key :
       {"estimation.enabled", "estimation.icr_expansion", "estimation.wheel.icr_offset_m",
        "estimation.wheel.slip_hold_s", "estimation.vo.harris.min_response",
        "estimation.vo.tracker.window_px", "estimation.vo.tracker.pyramid_levels",
        "estimation.vo.matcher.max_disparity_px", "estimation.vo.ransac.threshold_px",
        "estimation.vo.refinement.huber_px", "estimation.vo.seed",
        "estimation.vo.max_acceleration_mps2", "estimation.fusion.rules_file",
        "estimation.fusion.weight_rise_time_s", "estimation.min_inliers_for_slip",
        "estimation.vo_coast_time_s", "estimation.ekf.gyro_std"}) {
    EXPECT_EQ(paths.count(key), 1u) << key;
  }
  // The wheels' geometry and the IMU's calibration are the given calibration's.
  for (const char* key : {"estimation.wheel.sprocket_radius_m", "estimation.wheel.track_gauge_m",
                          "estimation.wheel.icr_expansion", "estimation.wheel.ticks_per_rev",
                          "estimation.wheel.estimate_slip", "estimation.imu"}) {
    EXPECT_EQ(paths.count(key), 0u) << key;
  }
  EXPECT_EQ(paths.size(), 85u);
}

// Each key set alone through --set to a valid value other than its default reaches the
// options the runner builds; then all of them at once.
TEST(EstimationOptionsTest, EveryKeyReachesTheBuiltOptions) {
  std::vector<scenario::Override> all;
  for (const key_walk::ScalarKey& k : EstimationKeys()) {
    bool reached = false;
    // An enum's other value by name; a string's, a rule file.
    const std::string other =
        k.path == "estimation.fusion.method" ? "covariance" : "walk_rules.fll";
    for (const std::string& value : key_walk::OtherValues(k.value, other)) {
      const std::optional<scenario::Scenario> s = WithOverride(k.path, value);
      if (!s) continue;
      EXPECT_TRUE(key_walk::SameScalar(BuiltValue(*s, k.path), value))
          << k.path << " set to " << value << ", built " << BuiltValue(*s, k.path);
      EXPECT_FALSE(key_walk::SameScalar(BuiltValue(scenario::Scenario{}, k.path), value))
          << k.path << ": " << value << " is its default";
      all.push_back({k.path, value});
      reached = true;
      break;
    }
    EXPECT_TRUE(reached) << k.path << ": no other value tried is valid";
  }
  const scenario::Scenario s = scenario::ParseScenario(kMinimal, "walk.yaml", all);
  for (const scenario::Override& o : all) {
    EXPECT_TRUE(key_walk::SameScalar(BuiltValue(s, o.key), o.value)) << o.key;
  }
}

TEST(EstimationOptionsTest, CalibrationFieldsComeFromTheGivenCalibration) {
  scenario::Scenario s = scenario::ParseScenario(kMinimal, "walk.yaml");
  s.robot.encoders.ticks_per_rev = 2048;
  calibration::RobotCalibration given = GivenCalibration();
  given.imu.camera_time_offset_s = 0.004;
  estimation::LocalizationOptions built = runner::LocalizationOptionsOf(s, given);
  EXPECT_EQ(built.wheel.sprocket_radius_m, 0.101);
  EXPECT_EQ(built.wheel.right_sprocket_radius_m, 0.099);
  EXPECT_EQ(built.wheel.track_gauge_m, 0.52);
  EXPECT_EQ(built.wheel.ticks_per_rev, 2048);
  EXPECT_EQ(built.imu.camera_time_offset_s, 0.004);
  // χ: the scenario's fallback, 1.239 (the hard floor's calibration), unless the given
  // calibration has its own.
  EXPECT_EQ(built.wheel.icr_expansion, 1.239);
  given.vehicle.icr_expansion = 1.1;
  built = runner::LocalizationOptionsOf(s, given);
  EXPECT_EQ(built.wheel.icr_expansion, 1.1);
}

TEST(EstimationOptionsTest, PresetsHoldTheRobotsAndTheCarsBounds) {
  const estimation::StereoVisualOdometryOptions robot =
      estimation::StereoVisualOdometryOptions::TrackedRobot();
  EXPECT_EQ(robot.max_translation_per_frame_m, 0.5);
  EXPECT_EQ(robot.max_rotation_per_frame_deg, 20.0);
  EXPECT_EQ(robot.max_acceleration_mps2, 8.0);
  EXPECT_EQ(robot.max_angular_acceleration_dps2, 1000.0);
  EXPECT_EQ(robot.max_rotation_prior_error_deg, 2.0);
  const estimation::StereoVisualOdometryOptions car =
      estimation::StereoVisualOdometryOptions::KittiCar();
  EXPECT_EQ(car.max_translation_per_frame_m, 3.0);
  EXPECT_EQ(car.max_rotation_per_frame_deg, 30.0);
  EXPECT_EQ(car.max_acceleration_mps2, 30.0);
  EXPECT_EQ(car.max_angular_acceleration_dps2, 1000.0);
  EXPECT_EQ(car.max_rotation_prior_error_deg, 2.0);
  // Apart from the bounds the two are the same, and the car's are the in-class defaults.
  estimation::StereoVisualOdometryOptions robot_with_car_bounds = robot;
  robot_with_car_bounds.max_translation_per_frame_m = car.max_translation_per_frame_m;
  robot_with_car_bounds.max_rotation_per_frame_deg = car.max_rotation_per_frame_deg;
  robot_with_car_bounds.max_acceleration_mps2 = car.max_acceleration_mps2;
  EXPECT_EQ(archive::ToYaml(archive::Write(robot_with_car_bounds)),
            archive::ToYaml(archive::Write(car)));
  EXPECT_EQ(archive::ToYaml(archive::Write(car)),
            archive::ToYaml(archive::Write(estimation::StereoVisualOdometryOptions{})));

  // A scenario's default is the robot's; the KITTI twin sets the car's bounds.
  const scenario::Scenario s = scenario::ParseScenario(kMinimal, "walk.yaml");
  EXPECT_EQ(archive::ToYaml(archive::Write(s.estimation.localization)),
            archive::ToYaml(archive::Write(estimation::LocalizationOptions::TrackedRobot())));
  EXPECT_EQ(archive::ToYaml(archive::Write(s.estimation.localization.vo)),
            archive::ToYaml(archive::Write(robot)));
  const scenario::Scenario twin =
      scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/kitti_twin.yaml");
  EXPECT_EQ(archive::ToYaml(archive::Write(twin.estimation.localization.vo)),
            archive::ToYaml(archive::Write(car)));
}

// The old keys of the section, set through --set to a value other than the default,
// land in the options the runner builds (KeyAliasesTest reads every alias in files and
// overrides alike).
TEST(EstimationOptionsTest, EveryAliasCarriesItsValueToTheBuiltOptions) {
  const archive::Node defaults = archive::Write(scenario::Scenario{});
  int aliases = 0;
  for (const scenario::KeyAlias& alias : scenario::ScenarioKeyAliases()) {
    if (!scenario::KeyWithin(alias.old_key, "estimation")) continue;
    SCOPED_TRACE(alias.old_key);
    ++aliases;
    const archive::Node* default_value = key_walk::NodeAt(defaults, alias.new_key);
    ASSERT_NE(default_value, nullptr);
    std::optional<scenario::Scenario> by_old;
    std::string value;
    for (const std::string& v : key_walk::OtherValues(*default_value, "walk_rules.fll")) {
      if ((by_old = WithOverride(alias.old_key, v))) {
        value = v;
        break;
      }
    }
    ASSERT_TRUE(by_old.has_value()) << "no other value tried is valid";
    EXPECT_TRUE(key_walk::SameScalar(BuiltValue(*by_old, alias.new_key), value));
  }
  EXPECT_EQ(aliases, 11);
}

// The old key of the fusion rule file is resolved beside the scenario file, as the new one.
TEST(EstimationOptionsTest, OldFusionRulesKeyIsFoundBesideTheScenario) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "estimation_options_rules";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "rules.fll") << "# rules\n";
  std::ofstream(dir / "scene.yaml") << kMinimal << "estimation: {fusion_rules: rules.fll}\n";
  const scenario::Scenario s = scenario::LoadScenario((dir / "scene.yaml").string());
  EXPECT_EQ(s.estimation.localization.fusion.rules_file,
            (std::filesystem::absolute(dir) / "rules.fll").lexically_normal().string());
}

}  // namespace
}  // namespace trackbed
