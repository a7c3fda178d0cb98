// Scenario files: defaults, exact round trips, and errors that name the source
// (file or --set override), the full dotted key and the reason.
#include "trackbed/scenario/scenario_yaml.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>

#include <gtest/gtest.h>

namespace trackbed::scenario {
namespace {

// The smallest valid scenario: a path drive needs its waypoints.
constexpr char kMinimal[] = "drive:\n  waypoints: [[0, 0], [5, 0]]\n";

// The message ParseScenario throws for `text` (empty when it does not throw).
std::string ErrorOf(const std::string& text, const std::vector<Override>& overrides = {}) {
  try {
    ParseScenario(text, "test.yaml", overrides);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

std::string RoundTrip(const std::string& text) {
  return ScenarioToYaml(ParseScenario(text, "round_trip.yaml"));
}

TEST(ScenarioYamlTest, MinimalFileTakesStructDefaults) {
  const Scenario s = ParseScenario(kMinimal, "test.yaml");
  const Scenario defaults;
  EXPECT_EQ(s.seed, defaults.seed);
  EXPECT_EQ(s.duration_s, defaults.duration_s);
  EXPECT_EQ(s.scene.name, "unnamed");
  EXPECT_EQ(s.scene.world.physics_step_s, 0.001);
  EXPECT_EQ(s.scene.terrain.extent_m, defaults.scene.terrain.extent_m);
  EXPECT_EQ(s.scene.terrain.default_material, "hard_floor");
  EXPECT_TRUE(s.scene.objects.empty());
  EXPECT_EQ(s.robot.vehicle.mass_kg, 40.0);
  EXPECT_EQ(s.robot.vehicle.hull_size_m, defaults.robot.vehicle.hull_size_m);
  EXPECT_EQ(s.robot.vehicle.motor.max_torque_nm, 20.0);
  EXPECT_EQ(s.robot.encoders.ticks_per_rev, 4096);
  EXPECT_FALSE(s.robot.imu.gyro_noise_density);  // the realism profile's part
  EXPECT_EQ(*WithRealismResolved(s).robot.imu.gyro_noise_density,
            *robot::WithImuPartResolved({}, robot::Realism::kTypical).gyro_noise_density);
  EXPECT_EQ(s.drive.mode, DriveSpec::Mode::kPath);
  ASSERT_EQ(s.drive.waypoints.size(), 2u);
  EXPECT_EQ(s.drive.waypoints[1], Eigen::Vector2d(5.0, 0.0));
  EXPECT_EQ(s.drive.laps, 1);
  EXPECT_EQ(s.drive.pursuit.speed_mps, 0.4);
  EXPECT_EQ(s.outputs.save_images, "none");
}

TEST(ScenarioYamlTest, WriterEmitsEveryKeyWithShortestDoubles) {
  Scenario s = ParseScenario(kMinimal, "test.yaml");
  s.duration_s = 1.0 / 3.0;
  s.robot.imu.rate_hz = 1e3 / 7.0;
  s.robot.imu.gyro_noise_density = 1.6968e-4;
  s.seed = 18446744073709551615u;
  const std::string text = ScenarioToYaml(s);
  EXPECT_NE(text.find("seed: 18446744073709551615\n"), std::string::npos) << text;
  EXPECT_NE(text.find("duration_s: 0.3333333333333333\n"), std::string::npos) << text;
  EXPECT_NE(text.find("    physics_step_s: 0.001\n"), std::string::npos) << text;
  EXPECT_NE(text.find("    gravity_mps2: 9.81\n"), std::string::npos) << text;
  EXPECT_NE(text.find("    extent_m: [-5, -5, 5, 5]\n"), std::string::npos) << text;
  EXPECT_NE(text.find("    gyro_noise_density: 0.00016968\n"), std::string::npos) << text;
  EXPECT_NE(text.find("    hull_contact_stiffness_npm: 200000\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  waypoints: [[0, 0], [5, 0]]\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  script: []\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  save_images: none\n"), std::string::npos) << text;
  const Scenario back = ParseScenario(text, "written.yaml");
  EXPECT_EQ(ScenarioToYaml(back), text);
  EXPECT_EQ(back.duration_s, s.duration_s);
  EXPECT_EQ(back.robot.imu.rate_hz, s.robot.imu.rate_hz);
  EXPECT_EQ(back.seed, s.seed);
}

TEST(ScenarioYamlTest, LongListsWrapAndRoundTrip) {
  Scenario s = ParseScenario(kMinimal, "test.yaml");
  for (int k = 0; k < 40; ++k) s.drive.waypoints.emplace_back(0.1 * k, std::sin(0.1 * k));
  const std::string text = ScenarioToYaml(s);
  EXPECT_NE(text.find("  waypoints:\n    [[0, 0], [5, 0], [0, 0], [0.1, 0.09983341664682815],"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\n     [0."), std::string::npos) << text;
  const Scenario back = ParseScenario(text, "written.yaml");
  EXPECT_EQ(back.drive.waypoints, s.drive.waypoints);
  EXPECT_EQ(ScenarioToYaml(back), text);
}

TEST(ScenarioYamlTest, RoundTripIsExact) {
  const std::string text = R"(
seed: 7
duration_s: 120
scene:
  name: "corridor: east wing"
  world: {physics_step_s: 1e-5, gravity_mps2: 9.81}
  terrain:
    extent_m: [-2.5, -1, 30, 4.2]
    cell_size_m: 0.1
    roughness: {undulation_amplitude_m: 0.3333333333333333, slope_x: -0.02}
    default_material: paving
    materials:
      - {name: wet_clay, cohesion_pa: 4140, friction_angle_deg: 13, shear_modulus_m: 0.01,
         bekker_kc: 12700, bekker_kphi: 1555950, bekker_n: 0.5, albedo: 0.35}
    regions:
      - {material: wet_clay, shape: circle, center: [3, 1], radius_m: 1.5}
      - {material: grass, min: [10, -1], max: [12, 4.2]}
  objects:
    - {type: wall, from: [0, 2], to: [30, 2.7]}
    - {type: bench, center: [4, -0.5], size_m: [1.5, 0.4, 0.45], yaw_deg: 12.5}
    - {type: tree, center: [20, 3], radius_m: 0.15, height_m: 6, base_z_m: -0.1}
    - {type: post, center: [1e-3, 0.1], radius_m: 0.05, height_m: 1}
robot:
  start: {x_m: 0.5, y_m: 0.1, yaw_deg: 90}
  vehicle: {mass_kg: 42.5, motor: {max_torque_nm: 25}}
  stereo: {enabled: true, baseline_m: 0.15}
drive:
  mode: script
  script:
    - {t_s: 0, v_mps: 0.4, yaw_rate_radps: 0}
    - {t_s: 5, left_mps: 0.2, right_mps: 0.4}
outputs: {save_images: kitti}
)";
  const std::string first = RoundTrip(text);
  const std::string second = RoundTrip(first);
  const std::string third = RoundTrip(second);
  EXPECT_EQ(first, second);
  EXPECT_EQ(second, third);
  EXPECT_NE(first.find("name: \"corridor: east wing\""), std::string::npos) << first;
  EXPECT_NE(first.find("physics_step_s: 0.00001"), std::string::npos) << first;
  EXPECT_NE(first.find("undulation_amplitude_m: 0.3333333333333333"), std::string::npos) << first;
  EXPECT_NE(first.find("yaw_deg: 12.5"), std::string::npos) << first;
  EXPECT_NE(first.find("center: [0.001, 0.1]"), std::string::npos) << first;
  EXPECT_NE(first.find("base_z_m: -0.1"), std::string::npos) << first;
  EXPECT_EQ(first.find("base_z_m: .nan"), std::string::npos) << first;
  EXPECT_NE(first.find("- {t_s: 5, left_mps: 0.2, right_mps: 0.4}"), std::string::npos) << first;
}

TEST(ScenarioYamlTest, RepositoryScenesLoadAndRoundTrip) {
  int scenes = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(TRACKBED_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    // The examples on a real elevation model and on packaged mesh files need the files
    // scripts/setup.sh installs.
    const std::string name = entry.path().filename().string();
    const std::string needed =
        name == "olinda_dem.yaml"
            ? "/usr/local/share/trackbed/r-cran-stars/tif/olinda_dem_utm25s.tif"
            : (name == "mesh_props.yaml"
                   ? "/usr/local/share/trackbed/assimp-testmodels/OBJ/spider.obj"
                   : "");
    if (!needed.empty() && !std::filesystem::exists(needed)) {
      std::cout << "not loaded: " << entry.path() << " (" << needed << " absent)\n";
      continue;
    }
    ++scenes;
    const std::string first = ScenarioToYaml(LoadScenario(entry.path().string()));
    EXPECT_EQ(RoundTrip(first), first) << entry.path();
  }
  EXPECT_GT(scenes, 0);
}

TEST(ScenarioYamlTest, YawDegreesRoundTripExactlyForAnyRadians) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> yaw(-4.0 * M_PI, 4.0 * M_PI);
  for (int k = 0; k < 500; ++k) {
    Scenario s = ParseScenario(kMinimal, "test.yaml");
    s.scene.objects.resize(1);
    s.scene.objects[0].yaw_rad = k == 0 ? M_PI / 2.0 : yaw(rng);
    const std::string first = ScenarioToYaml(s);
    const Scenario back = ParseScenario(first, "first.yaml");
    // Within one double of the original, and the text is a fixed point from here on.
    EXPECT_LE(std::abs(back.scene.objects[0].yaw_rad - s.scene.objects[0].yaw_rad),
              2.0 * std::abs(std::nextafter(s.scene.objects[0].yaw_rad, 0.0) -
                             s.scene.objects[0].yaw_rad));
    ASSERT_EQ(ScenarioToYaml(back), first) << "yaw_rad " << s.scene.objects[0].yaw_rad;
  }
}

TEST(ScenarioYamlTest, TypedDegreesAreWrittenAsTyped) {
  std::string text = std::string(kMinimal) + "scene:\n  objects:\n";
  std::vector<std::string> typed;
  for (int tenths = -3600; tenths <= 3600; tenths += 7) {
    typed.push_back(std::to_string(tenths / 10) + "." + std::to_string(std::abs(tenths) % 10));
    if (tenths < 0 && tenths > -10) typed.back() = "-" + typed.back();
    if (typed.back().substr(typed.back().size() - 2) == ".0")
      typed.back().resize(typed.back().size() - 2);
    text += "    - {type: box, yaw_deg: " + typed.back() + "}\n";
  }
  const std::string written = RoundTrip(text);
  for (const std::string& deg : typed) {
    EXPECT_NE(written.find("yaw_deg: " + deg + ", "), std::string::npos) << deg;
  }
}

TEST(ScenarioYamlTest, UnknownKeyNamesFileAndDottedKey) {
  EXPECT_EQ(ErrorOf(std::string(kMinimal) + "sede: 3\n"),
            "test.yaml: sede: unknown key (allowed: seed, duration_s, scene, robot, drive, "
            "estimation, navigation, teach_repeat, outputs)");
  const std::string nested = ErrorOf(std::string(kMinimal) + "robot:\n  vehicle:\n    mas_kg: 3\n");
  EXPECT_EQ(nested.rfind("test.yaml: robot.vehicle.mas_kg: unknown key (allowed: mass_kg, ", 0), 0u)
      << nested;
  EXPECT_NE(nested.find("motor)"), std::string::npos) << nested;
  EXPECT_EQ(ErrorOf(std::string(kMinimal) + "scene: {objects: [{type: post, size_m: [1, 1, 1]}]}"),
            "test.yaml: scene.objects[0].size_m: unknown key (allowed: type, center, radius_m, "
            "height_m, appearance, albedo, base_z_m, collides)");
}

TEST(ScenarioYamlTest, ScatterAddsObjectsClearOfTheRouteAndNamesBadKeys) {
  const std::string scene =
      "drive:\n  waypoints: [[-5, 0], [5, 0]]\n"
      "scene:\n  terrain: {extent_m: [-20, -10, 20, 10], default_material: grass}\n"
      "  objects: [{type: post, center: [9, 9]}]\n"
      "  scatter: [{type: tree, density_per_100m2: 4, clearance_m: 1}]\n";
  const Scenario s = ParseScenario(scene, "test.yaml");
  const std::vector<sim::StaticObject> objects = SceneObjects(s);
  ASSERT_GT(objects.size(), 25u);      // 800 m² at 4 per 100 m²: 32, less the route's strip
  EXPECT_EQ(objects[0].kind, "post");  // the listed ones first
  for (std::size_t k = 1; k < objects.size(); ++k) {
    const Eigen::Vector2d c = objects[k].center_m;
    const double from_route = std::abs(c.x()) <= 5.0 ? std::abs(c.y()) : 1e9;
    EXPECT_GE(from_route, 1.0 + objects[k].radius_m) << c.transpose();
  }
  // The same seed scatters the same; the scenario written out reads back the same.
  EXPECT_EQ(SceneObjects(ParseScenario(RoundTrip(scene), "again.yaml")).size(), objects.size());
  EXPECT_EQ(ErrorOf(std::string(kMinimal) + "scene: {scatter: [{type: wall}]}"),
            "test.yaml: scene.scatter[0].type: must be tree, post, cylinder, bench or box (got "
            "'wall')");
  EXPECT_EQ(ErrorOf(std::string(kMinimal) +
                    "scene: {terrain: {cell_size_m: 2, extent_m: [0, 0, 4000, 4000]}, "
                    "scatter: [{density_per_100m2: 10}]}"),
            "test.yaml: scene.scatter[0].density_per_100m2: gives more than a million objects "
            "over the region");
  EXPECT_EQ(ErrorOf(std::string(kMinimal) + "scene: {scatter: [{materials: [lava]}]}")
                .rfind("test.yaml: scene.scatter[0].materials[0]: ", 0),
            0u);
}

// YAML is UTF-8 text: a name with other bytes is refused where it is read, naming its
// key, in the file and in `--set` alike (it would otherwise reach the
// run folder's scenario.yaml as invalid text).
TEST(ScenarioYamlTest, TextThatIsNotUtf8NamesItsKey) {
  EXPECT_EQ(ErrorOf(std::string(kMinimal) + "scene: {name: \"bad\xff\"}\n"),
            "test.yaml: scene.name: not UTF-8 text");
  EXPECT_EQ(ErrorOf(std::string(kMinimal) + "scene: {objects: [{appearance: \"\xed\xa0\x80\"}]}\n"),
            "test.yaml: scene.objects[0].appearance: not UTF-8 text");
  EXPECT_EQ(ErrorOf(kMinimal, {{"scene.name", "bad\xc0\xaf"}}),
            "--set scene.name=bad\xc0\xaf: scene.name: not UTF-8 text");
  EXPECT_EQ(ErrorOf(std::string(kMinimal) + "scene: {name: \"caf\xc3\xa9\"}\n"), "");
}

// A lens whose distorted radius stops growing before the image's border (k1 −1.5: it
// peaks at r = 0.58 of the normalised radius, inside the 80° image) is refused when the
// scenario is read, naming its key, not when the renderer first needs it.
TEST(ScenarioYamlTest, ALensThatDoesNotReachTheImagesBorderNamesItsKey) {
  const std::string error = ErrorOf(
      std::string(kMinimal) +
      "robot: {stereo: {distortion: {model: radial_tangential, k1: -1.5, k2: 0, p1: 0, p2: 0}}}\n");
  EXPECT_EQ(
      error.rfind("test.yaml: robot.stereo.distortion: the lens cannot be inverted at pixel (", 0),
      0u)
      << error;
  EXPECT_NE(error.find("of the 640 x 480 image at fx 381.361 px"), std::string::npos) << error;
  EXPECT_EQ(ErrorOf(std::string(kMinimal) +
                    "robot: {stereo: {distortion: {model: radial_tangential, k1: -0.28340811, k2: "
                    "0.07395907, p1: 0.00019359, p2: 1.76187114e-05}}}\n"),
            "");
}

TEST(ScenarioYamlTest, RegionRejectsKeysOfTheOtherShape) {
  const std::string error = ErrorOf(std::string(kMinimal) +
                                    "scene:\n  terrain:\n    regions:\n"
                                    "      - {material: clay, shape: circle, min: [0, 0]}\n");
  EXPECT_EQ(error,
            "test.yaml: scene.terrain.regions[0].min: unknown key (allowed: material, shape, "
            "center, radius_m)");
  EXPECT_EQ(ErrorOf(std::string(kMinimal) +
                    "scene: {terrain: {regions: [{material: clay, shape: disc}]}}"),
            "test.yaml: scene.terrain.regions[0].shape: must be one of rectangle, circle (got "
            "'disc')");
}

TEST(ScenarioYamlTest, TheBagsImagesNeedTheBagAndTheCamera) {
  const std::string m = kMinimal;
  const std::string why =
      "test.yaml: outputs.mcap_images: needs outputs.mcap: true and robot.stereo.enabled: true";
  EXPECT_EQ(ErrorOf(m + "outputs: {mcap: false, mcap_images: true}\n"), why);
  EXPECT_EQ(ErrorOf(m + "robot: {stereo: {enabled: false}}\noutputs: {mcap_images: true}\n"), why);
  EXPECT_EQ(ErrorOf(m + "outputs: {mcap: maybe}\n"),
            "test.yaml: outputs.mcap: expected true or false, got 'maybe'");
}

TEST(ScenarioYamlTest, WrongTypeNamesKeyAndExpectation) {
  const std::string m = kMinimal;
  EXPECT_EQ(ErrorOf(m + "duration_s: fast\n"),
            "test.yaml: duration_s: expected a number, got 'fast'");
  EXPECT_EQ(ErrorOf(m + "duration_s: \"20\"\n"),
            "test.yaml: duration_s: expected a number, got the quoted string \"20\"");
  EXPECT_EQ(ErrorOf(m + "robot: {vehicle: {road_wheels_per_track: 6.5}}\n"),
            "test.yaml: robot.vehicle.road_wheels_per_track: expected an integer, got '6.5'");
  EXPECT_EQ(ErrorOf(m + "seed: -1\n"),
            "test.yaml: seed: expected an integer in [0, 2^64), got '-1'");
  EXPECT_EQ(ErrorOf("drive: {waypoints: [[0, 0], [5, 0]], closed: yes}\n"),
            "test.yaml: drive.closed: expected true or false, got 'yes'");
  EXPECT_EQ(ErrorOf(m + "scene: 5\n"), "test.yaml: scene: expected a map, got '5'");
  EXPECT_EQ(ErrorOf(m + "robot: {vehicle: {hull_size_m: [1, 2]}}\n"),
            "test.yaml: robot.vehicle.hull_size_m: expected a list of 3 numbers, got a list of 2");
  EXPECT_EQ(ErrorOf(m + "scene: {objects: {type: box}}\n"),
            "test.yaml: scene.objects: expected a list, got a map");
  EXPECT_EQ(ErrorOf(m + "scene: {name: [a]}\n"),
            "test.yaml: scene.name: expected a string, got a list of 1");
  EXPECT_EQ(ErrorOf("- 1\n"), "test.yaml: expected a map of scenario keys, got a list of 1");
  EXPECT_EQ(ErrorOf(m + "seed: 1\nseed: 2\n"), "test.yaml: seed: duplicate key");
}

TEST(ScenarioYamlTest, OutOfRangeValueReportsFullDottedKey) {
  const std::string m = kMinimal;
  EXPECT_EQ(ErrorOf(m + "robot:\n  vehicle:\n    mass_kg: -1\n"),
            "test.yaml: robot.vehicle.mass_kg: must be > 0 (got -1)");
  EXPECT_EQ(ErrorOf(m + "robot: {vehicle: {motor: {max_torque_nm: 0}}}\n"),
            "test.yaml: robot.vehicle.motor.max_torque_nm: must be > 0 (got 0)");
  EXPECT_EQ(ErrorOf(m + "duration_s: 0\n"), "test.yaml: duration_s: must be in (0, 1e6] (got 0)");
  EXPECT_EQ(ErrorOf(m + "robot: {vehicle: {station_x_m: [0.1, -0.1, 0.1]}}\n"),
            "test.yaml: robot.vehicle.station_x_m[2]: must be at least 1 mm from "
            "station_x_m[0] (got 0.1 and 0.1)");
  EXPECT_EQ(ErrorOf(m + "robot: {vehicle: {station_x_m: [0.1, 0.3]}}\n"),
            "test.yaml: robot.vehicle.station_x_m[1]: must lie inside the track's contact "
            "length (|x| < 0.275)");
  EXPECT_EQ(ErrorOf(m + "scene: {terrain: {soil_variation: {amplitude: 2}}}\n"),
            "test.yaml: scene.terrain.soil_variation.amplitude: must be in [0, 0.9] (got 2)");
  EXPECT_EQ(ErrorOf(m + "estimation: {min_inliers_for_slip: -5}\n"),
            "test.yaml: estimation.min_inliers_for_slip: must be >= 0 (got -5)");
  EXPECT_EQ(ErrorOf(m + "estimation: {wheel: {slip_filter_time_s: -0.1}}\n"),
            "test.yaml: estimation.wheel.slip_filter_time_s: must be >= 0 (got -0.1)");
  EXPECT_EQ(ErrorOf(m + "estimation: {vo: {tracker: {window_px: 4}}}\n"),
            "test.yaml: estimation.vo.tracker.window_px: must be odd and >= 5 (got 4)");
  EXPECT_EQ(ErrorOf(m + "estimation: {ekf: {wheel_yaw_rate_std: 0}}\n"),
            "test.yaml: estimation.ekf.wheel_yaw_rate_std: must be > 0 (got 0)");
  EXPECT_EQ(ErrorOf(m + "estimation: {ekf: {wheel_yaw_std: 0.5}}\n")
                .rfind("test.yaml: estimation.ekf.wheel_yaw_std: unknown key (allowed: ", 0),
            0u);
  EXPECT_EQ(ErrorOf(m + "robot: {stereo: {exposure_time_s: 0.2}}\n"),
            "test.yaml: robot.stereo.exposure_time_s: must be in [0, 0.1] (got 0.2)");
  EXPECT_EQ(ErrorOf(m + "robot: {stereo: {exposure_samples: 0}}\n"),
            "test.yaml: robot.stereo.exposure_samples: must be in [1, 64] (got 0)");
  EXPECT_EQ(ErrorOf(m + "robot: {stereo: {edge_antialiasing_samples: 2}}\n"),
            "test.yaml: robot.stereo.edge_antialiasing_samples: must be 1 (off) or 4, the sample "
            "counts the renderer draws (got 2)");
  EXPECT_EQ(ErrorOf(m + "outputs: {save_images: png}\n"),
            "test.yaml: outputs.save_images: must be none or kitti (got 'png')");
  EXPECT_EQ(ErrorOf("drive: {waypoints: [[0, 0]]}\n"),
            "test.yaml: drive.waypoints: mode path needs at least 2 waypoints (got 1)");
  EXPECT_EQ(ErrorOf("drive: {mode: script}\n"),
            "test.yaml: drive.script: mode script needs at least 1 command");
  EXPECT_EQ(
      ErrorOf(m + "scene: {terrain: {regions: [{material: mud, min: [0, 0], max: [1, 1]}]}}"),
      "test.yaml: scene.terrain.regions[0].material: unknown material 'mud' (known: "
      "hard_floor, paving, asphalt, lete_sand, dry_sand, dry_sand_wong, sandy_loam, clay, grass, "
      "north_gower_clayey_loam_wong)");
}

TEST(ScenarioYamlTest, ListIndexInKey) {
  const std::string m = kMinimal;
  EXPECT_EQ(ErrorOf(m + "scene:\n  objects:\n    - {type: box}\n"
                        "    - {type: tree, radius_m: 0}\n"),
            "test.yaml: scene.objects[1].radius_m: must be > 0 (got 0)");
  EXPECT_EQ(ErrorOf("drive: {waypoints: [[0, 0], [5, x]]}\n"),
            "test.yaml: drive.waypoints[1][1]: expected a number, got 'x'");
  EXPECT_EQ(ErrorOf(m + "scene: {objects: [{type: box, center: [1, .inf]}]}\n"),
            "test.yaml: scene.objects[0].center[1]: must be a finite number (got inf)");
  EXPECT_EQ(ErrorOf("drive:\n  mode: script\n  script:\n    - {t_s: 2}\n    - {t_s: 1}\n"),
            "test.yaml: drive.script[1].t_s: must not be earlier than the previous command's t_s");
}

TEST(ScenarioYamlTest, ScriptEntryUsesEitherTwistOrTrackSpeeds) {
  const Scenario s = ParseScenario(
      "drive:\n  mode: script\n  script:\n    - {t_s: 0, v_mps: 0.4}\n"
      "    - {t_s: 5, left_mps: 0.2, right_mps: 0.3}\n",
      "test.yaml");
  ASSERT_EQ(s.drive.script.size(), 2u);
  EXPECT_FALSE(s.drive.script[0].track_speeds);
  EXPECT_EQ(s.drive.script[0].v_mps, 0.4);
  EXPECT_TRUE(s.drive.script[1].track_speeds);
  EXPECT_EQ(s.drive.script[1].right_mps, 0.3);
  EXPECT_EQ(ErrorOf("drive: {mode: script, script: [{t_s: 0, v_mps: 1, left_mps: 1}]}\n"),
            "test.yaml: drive.script[0]: use either v_mps, yaw_rate_radps or left_mps, right_mps, "
            "not both");
}

TEST(ScenarioYamlTest, MissingFileSaysCannotRead) {
  const std::string path = ::testing::TempDir() + "/no_such_scenario.yaml";
  try {
    LoadScenario(path);
    FAIL() << "no exception";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot read file: No such file or directory");
    EXPECT_EQ(e.source(), path);
  }
}

// An encoder dropout names its track and span; a bad one names the entry and field.
TEST(ScenarioYamlTest, EncoderDropoutsAreReadAndCheckedByEntry) {
  const Scenario s = ParseScenario(
      std::string(kMinimal) +
          "robot: {encoders: {dropouts_s: [{track: left, start_s: 2, duration_s: 1}]}}\n",
      "d.yaml");
  ASSERT_EQ(s.robot.encoders.dropouts_s.size(), 1u);
  EXPECT_TRUE(s.robot.encoders.InDropout(0, 2.5));
  EXPECT_FALSE(s.robot.encoders.InDropout(1, 2.5));
  EXPECT_FALSE(s.robot.encoders.InDropout(0, 3.0));
  for (const auto& [entry, message] : std::vector<std::pair<std::string, std::string>>{
           {"{track: middle, start_s: 2, duration_s: 1}",
            "robot.encoders.dropouts_s[0].track: must be one of left, right, both (got 'middle')"},
           {"{track: both, start_s: -1, duration_s: 1}",
            "robot.encoders.dropouts_s[0].start_s: must be >= 0 (got -1)"},
           {"{track: both, start_s: 1, duration_s: 0}",
            "robot.encoders.dropouts_s[0].duration_s: must be > 0 (got 0)"}}) {
    try {
      ParseScenario(std::string(kMinimal) + "robot: {encoders: {dropouts_s: [" + entry + "]}}\n",
                    "d.yaml");
      FAIL() << entry;
    } catch (const ScenarioError& e) {
      EXPECT_EQ(std::string(e.what()), "d.yaml: " + message);
    }
  }
}

TEST(ScenarioYamlTest, LoadsFileAndNamesItInErrors) {
  const std::string path = ::testing::TempDir() + "/scenario_yaml_test.yaml";
  std::ofstream(path) << kMinimal << "duration_s: 12\nrobot: {imu: {rate_hz: 0}}\n";
  try {
    LoadScenario(path);
    FAIL() << "no exception";
  } catch (const ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": robot.imu.rate_hz: must be in [1, 10000] (got 0)");
    EXPECT_EQ(e.key(), "robot.imu.rate_hz");
  }
  const Scenario s = LoadScenario(path, {{"robot.imu.rate_hz", "400"}});
  EXPECT_EQ(s.duration_s, 12.0);
  EXPECT_EQ(s.robot.imu.rate_hz, 400.0);
  std::remove(path.c_str());
}

TEST(ScenarioYamlTest, SyntaxErrorHasLineAndColumn) {
  const std::string error = ErrorOf("seed: 1\nscene:\n  name: x\n  world: {physics_step_s: 1\n");
  EXPECT_EQ(error.rfind("test.yaml: invalid YAML at line ", 0), 0u) << error;
  EXPECT_NE(error.find("line 5, column 1: "), std::string::npos) << error;
}

TEST(ScenarioYamlTest, ParseOverrideSplitsAtFirstEquals) {
  const Override o = ParseOverride("drive.waypoints=[[0,0],[5,0]]");
  EXPECT_EQ(o.key, "drive.waypoints");
  EXPECT_EQ(o.value, "[[0,0],[5,0]]");
  EXPECT_EQ(ParseOverride("scene.name=a=b").value, "a=b");
  EXPECT_EQ(ParseOverride("scene.objects[2].height_m=1").key, "scene.objects[2].height_m");
  try {
    ParseOverride("duration_s");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "--set: expected key=value, got 'duration_s'");
  }
  EXPECT_THROW(ParseOverride("=3"), std::invalid_argument);
  EXPECT_THROW(ParseOverride("robot..mass_kg=3"), std::invalid_argument);
  EXPECT_THROW(ParseOverride("scene.objects[x].height_m=3"), std::invalid_argument);
}

TEST(ScenarioYamlTest, OverrideSetsExistingKeys) {
  const Scenario s = ParseScenario(
      std::string(kMinimal) + "duration_s: 60\n", "test.yaml",
      {ParseOverride("duration_s=20"), ParseOverride("drive.waypoints=[[0, 0], [5, 0], [5, 5]]"),
       ParseOverride("robot.vehicle.hull_size_m=[1, 0.5, 0.3]")});
  EXPECT_EQ(s.duration_s, 20.0);
  EXPECT_EQ(s.drive.waypoints.size(), 3u);
  EXPECT_EQ(s.robot.vehicle.hull_size_m, Eigen::Vector3d(1.0, 0.5, 0.3));
}

TEST(ScenarioYamlTest, OverrideCreatesMissingMapsWithDefaults) {
  const Scenario s =
      ParseScenario(kMinimal, "test.yaml", {ParseOverride("robot.vehicle.motor.max_torque_nm=30")});
  EXPECT_EQ(s.robot.vehicle.motor.max_torque_nm, 30.0);
  EXPECT_EQ(s.robot.vehicle.motor.max_speed_radps, 15.0);
  EXPECT_EQ(s.robot.vehicle.mass_kg, 40.0);
  const Scenario empty =
      ParseScenario("", "empty.yaml", {ParseOverride("drive.waypoints=[[0,0],[1,0]]")});
  EXPECT_EQ(empty.drive.waypoints.size(), 2u);
}

TEST(ScenarioYamlTest, OverrideIndexesListsInBothForms) {
  const std::string text =
      std::string(kMinimal) + "scene:\n  objects:\n    - {type: box}\n    - {type: post}\n";
  for (const char* key : {"scene.objects.1.height_m", "scene.objects[1].height_m"}) {
    const Scenario s = ParseScenario(text, "test.yaml", {{key, "3.5"}});
    EXPECT_EQ(s.scene.objects[1].height_m, 3.5) << key;
  }
  EXPECT_EQ(ErrorOf(text, {{"scene.objects.5.height_m", "1"}}),
            "--set scene.objects.5.height_m=1: scene.objects: index 5 is past the end (2 entries)");
  EXPECT_EQ(ErrorOf(text, {{"scene.objects[0][1]", "1"}}),
            "--set scene.objects[0][1]=1: scene.objects[0]: is not a list");
}

TEST(ScenarioYamlTest, BadOverrideIsAttributedToSet) {
  const std::string m = kMinimal;
  EXPECT_EQ(ErrorOf(m, {ParseOverride("robot.vehicle.mass_kg=-1")}),
            "--set robot.vehicle.mass_kg=-1: robot.vehicle.mass_kg: must be > 0 (got -1)");
  const std::string typo = ErrorOf(m, {ParseOverride("robot.vehicel.mass_kg=50")});
  EXPECT_EQ(typo,
            "--set robot.vehicel.mass_kg=50: robot.vehicel: unknown key (allowed: start, vehicle, "
            "encoders, imu, stereo, range_sensor, realism, imperfections, as_built_seed, "
            "calibration_dir, description)");
  EXPECT_EQ(ErrorOf(m, {ParseOverride("duration_s=soon")}),
            "--set duration_s=soon: duration_s: expected a number, got 'soon'");
  EXPECT_EQ(
      ErrorOf(m, {ParseOverride("drive.waypoints=[[0,0]")})
          .rfind("--set drive.waypoints=[[0,0]: drive.waypoints: cannot parse the value as YAML: ",
                 0),
      0u);
  // A bad value the file brought stays the file's, whatever the overrides touch.
  EXPECT_EQ(ErrorOf(m + "robot: {vehicle: {mass_kg: -1}}\n", {ParseOverride("duration_s=5")}),
            "test.yaml: robot.vehicle.mass_kg: must be > 0 (got -1)");
}

// A robot started beyond the terrain would fall with no ground under it; a command the
// sprocket motors cannot reach (15 rad/s × 0.10 m = 1.5 m/s by default) is refused, not
// saturated — in every form a speed can be given.
TEST(ScenarioYamlTest, StartOffTheTerrainAndUnreachableSpeedsAreRefused) {
  EXPECT_EQ(ErrorOf(kMinimal, {{"robot.start.x_m", "7"}}),
            "--set robot.start.x_m=7: robot.start: (7, 0) is outside scene.terrain.extent_m "
            "[-5, -5, 5, 5]: "
            "no ground there");
  EXPECT_EQ(ErrorOf(kMinimal, {{"robot.start.x_m", "5"}, {"robot.start.y_m", "-5"}}), "");
  const std::string top =
      " m/s, beyond the motors' top track speed 1.5 m/s (robot.vehicle.motor.max_speed_radps "
      "× sprocket_radius_m)";
  EXPECT_EQ(ErrorOf(kMinimal, {{"drive.speed_mps", "1e300"}}),
            "--set drive.speed_mps=1e300: drive.speed_mps: asks a track for 1e+300" + top);
  EXPECT_EQ(ErrorOf("drive:\n  mode: script\n  script:\n    - {t_s: 0, left_mps: 0.2, "
                    "right_mps: -2}\n"),
            "test.yaml: drive.script[0].right_mps: asks a track for 2" + top);
  // A twist: the faster track runs |v| + |ω|·W/2 = 1.2 + 1.5 · 0.25 = 1.575 m/s.
  EXPECT_EQ(ErrorOf("drive:\n  mode: script\n  script:\n    - {t_s: 0, v_mps: 0.2, "
                    "yaw_rate_radps: 0}\n    - {t_s: 1, v_mps: -1.2, yaw_rate_radps: 1.5}\n"),
            "test.yaml: drive.script[1].v_mps: asks a track for 1.575" + top);
  EXPECT_EQ(ErrorOf(kMinimal, {{"drive.speed_mps", "1.5"}}), "");
  // Faster motors raise the bound.
  EXPECT_EQ(
      ErrorOf(kMinimal, {{"drive.speed_mps", "2"}, {"robot.vehicle.motor.max_speed_radps", "25"}}),
      "");
}

// A terrain may be 10 km a side at any area (it is held in tiles); the camera's
// renderer meshes the whole grid, at most 16 million cells, unless it may draw the far
// ground coarser (terrain_full_detail_m > 0).
TEST(ScenarioYamlTest, TerrainBoundsAndTheRenderersLimitNameTheirKeys) {
  const std::string m = kMinimal;
  const std::string km = "scene: {terrain: {extent_m: [-500, -500, 500, 500]}}\n";
  EXPECT_EQ(ErrorOf(m + km), "");  // 100 million cells of 0.1 m, physics only
  EXPECT_EQ(ErrorOf(m + km + "robot: {stereo: {enabled: true}}\n"),
            "test.yaml: scene.terrain.cell_size_m: gives 100 million cells; with "
            "scene.appearance.terrain_full_detail_m 0 the camera's renderer meshes the whole "
            "grid and takes at most 16 million (set it > 0 to draw a window in detail and the "
            "rest coarser)");
  EXPECT_EQ(ErrorOf(m + "scene: {terrain: {extent_m: [-500, -500, 500, 500]}, appearance: "
                        "{terrain_full_detail_m: 2}}\nrobot: {stereo: {enabled: true}}\n"),
            "");
  EXPECT_EQ(ErrorOf(m + "scene: {terrain: {extent_m: [-5000, -5000, 5001, 0], cell_size_m: 2}}\n"),
            "test.yaml: scene.terrain.extent_m: must be at most 10000 m a side");
  EXPECT_EQ(ErrorOf(m + "scene: {terrain: {extent_m: [9000, 0, 10001, 5], cell_size_m: 2}}\n"),
            "test.yaml: scene.terrain.extent_m: must lie within ±10000 m of the origin (got "
            "10001)");
  EXPECT_EQ(ErrorOf(m + "scene: {terrain: {extent_m: [-5000, -5000, 5000, 5000], cell_size_m: "
                        "2}}\nrobot: {start: {x_m: 4000, y_m: -4000}}\n"),
            "");
}

TEST(ScenarioYamlTest, APosePathIsCarriedAtCarSpeedsAndCheckedOnTheTerrain) {
  const std::string pose_path = "drive:\n  mode: pose_path\n  waypoints: [[0, 0], [5, 0]]\n";
  // A carried body is not held to the motors' top track speed, only to a car's.
  EXPECT_EQ(ErrorOf(pose_path, {{"drive.speed_mps", "25"}}), "");
  EXPECT_NE(ErrorOf(pose_path, {{"drive.speed_mps", "120"}}).find("drive.speed_mps: must be in"),
            std::string::npos);
  EXPECT_EQ(ErrorOf(pose_path, {{"drive.waypoints[1]", "[6, 0]"}}),
            "--set drive.waypoints[1]=[6, 0]: drive.waypoints[1]: (6, 0) is outside "
            "scene.terrain.extent_m: a pose path rests on the ground");
  EXPECT_NE(ErrorOf(pose_path, {{"drive.waypoints[1]", "[0, 0]"}})
                .find("drive.waypoints[1]: "
                      "coincides with waypoint 0"),
            std::string::npos);
  EXPECT_NE(ErrorOf(pose_path, {{"teach_repeat.enabled", "true"}, {"robot.stereo.enabled", "true"}})
                .find("teach_repeat.enabled: teach & repeat drives the robot"),
            std::string::npos);
  EXPECT_EQ(ParseScenario(pose_path, "test.yaml").drive.mode, DriveSpec::Mode::kPosePath);
}

TEST(ScenarioYamlTest, TheDistanceBoundIsOffOrAtLeastOneBaseline) {
  EXPECT_EQ(ParseScenario(kMinimal, "test.yaml").teach_repeat.funnel_lane.max_milestone_overrun,
            2.0);
  EXPECT_EQ(ErrorOf(kMinimal, {{"teach_repeat.max_milestone_overrun", "0"}}), "");
  EXPECT_EQ(ErrorOf(kMinimal, {{"teach_repeat.max_milestone_overrun", "1.5"}}), "");
  EXPECT_NE(ErrorOf(kMinimal, {{"teach_repeat.max_milestone_overrun", "0.5"}})
                .find("teach_repeat.max_milestone_overrun: must be 0 (off) or >= 1 (got 0.5)"),
            std::string::npos);
  EXPECT_NE(ErrorOf(kMinimal, {{"teach_repeat.max_milestone_overrun", ".inf"}})
                .find("teach_repeat.max_milestone_overrun: must be 0 (off) or >= 1"),
            std::string::npos);
}

TEST(ScenarioYamlTest, APublishedCameraIsGivenByItsFocalLengthAndPrincipalPoint) {
  const Scenario s = ParseScenario(
      std::string(kMinimal) +
          "robot:\n  stereo:\n    width_px: 1241\n    height_px: 376\n"
          "    focal_length_px: 718.856\n    principal_point_px: [607.1928, 185.2157]\n",
      "test.yaml");
  const geometry::PinholeCamera K = s.robot.stereo.DesignIntrinsics();
  EXPECT_EQ(K.fx, 718.856);
  EXPECT_EQ(K.fy, 718.856);
  EXPECT_EQ(K.cx, 607.1928);
  EXPECT_EQ(K.cy, 185.2157);
  // Without them: hfov_deg and the image's centre.
  const geometry::PinholeCamera centred =
      ParseScenario(kMinimal, "test.yaml").robot.stereo.DesignIntrinsics();
  EXPECT_EQ(centred.cx, 319.5);
  EXPECT_NEAR(centred.fx, 320.0 / std::tan(40.0 * M_PI / 180.0), 1e-9);
  EXPECT_NE(ErrorOf(kMinimal, {{"robot.stereo.focal_length_px", "20"}})
                .find("robot.stereo.focal_length_px: too short for the image"),
            std::string::npos);
  EXPECT_NE(ErrorOf(kMinimal, {{"robot.stereo.principal_point_px", "[700, 200]"}})
                .find("robot.stereo.principal_point_px[0]: must be in"),
            std::string::npos);
}

TEST(ScenarioYamlTest, WallFromToBecomesRotatedBox) {
  const Scenario s = ParseScenario(
      std::string(kMinimal) + "scene:\n  objects:\n    - {type: wall, from: [1, 1], to: [4, 5]}\n",
      "test.yaml");
  ASSERT_EQ(s.scene.objects.size(), 1u);
  const sim::StaticObject& wall = s.scene.objects[0];
  EXPECT_EQ(wall.kind, "wall");
  EXPECT_EQ(wall.shape, sim::StaticObject::Shape::kBox);
  EXPECT_EQ(wall.appearance, "plain_paint");
  EXPECT_EQ(wall.center_m, Eigen::Vector2d(2.5, 3.0));
  EXPECT_DOUBLE_EQ(wall.yaw_rad, std::atan2(4.0, 3.0));
  EXPECT_DOUBLE_EQ(wall.size_m.x(), 5.0);
  EXPECT_EQ(wall.size_m.y(), 0.1);
  EXPECT_EQ(wall.size_m.z(), 2.5);
  EXPECT_TRUE(std::isnan(wall.base_z_m));
  // The yaw written is the shortest decimal whose units::Radians is exactly atan2(4, 3)
  // (one unit in the last place below its nearest decimal in degrees, 53.13010235415598).
  const std::string text = ScenarioToYaml(s);
  EXPECT_NE(text.find("    - type: wall\n      center: [2.5, 3]\n      size_m: [5, 0.1, 2.5]\n"
                      "      yaw_deg: 53.13010235415597\n      appearance: plain_paint\n"),
            std::string::npos)
      << text;
  EXPECT_EQ(RoundTrip(text), text);
  EXPECT_EQ(ErrorOf(std::string(kMinimal) + "scene: {objects: [{type: wall, from: [1, 1]}]}"),
            "test.yaml: scene.objects[0].to: missing: a wall given by from/to needs both");
}

TEST(ScenarioYamlTest, ObjectTypesPickShapeAndAppearance) {
  const Scenario s = ParseScenario(std::string(kMinimal) +
                                       "scene:\n  objects:\n    - {type: bench}\n"
                                       "    - {type: tree}\n    - {type: post, appearance: rust}\n"
                                       "    - {type: car, size_m: [4.2, 1.8, 1.5]}\n",
                                   "test.yaml");
  ASSERT_EQ(s.scene.objects.size(), 4u);
  EXPECT_EQ(s.scene.objects[0].shape, sim::StaticObject::Shape::kBox);
  EXPECT_EQ(s.scene.objects[0].appearance, "wood");
  EXPECT_EQ(s.scene.objects[1].shape, sim::StaticObject::Shape::kCylinder);
  EXPECT_EQ(s.scene.objects[1].appearance, "bark");
  EXPECT_EQ(s.scene.objects[2].appearance, "rust");
  // A parked car is a box to everything but the renderer, which draws its parts.
  EXPECT_EQ(s.scene.objects[3].shape, sim::StaticObject::Shape::kBox);
  EXPECT_EQ(s.scene.objects[3].appearance, "metal");
  EXPECT_TRUE(s.scene.objects[3].collides);
  EXPECT_EQ(ErrorOf(std::string(kMinimal) + "scene: {objects: [{type: rock}]}"),
            "test.yaml: scene.objects[0].type: must be one of wall, box, bench, cylinder, tree, "
            "post, door, poster, mesh, car (got 'rock')");
}

}  // namespace
}  // namespace trackbed::scenario
