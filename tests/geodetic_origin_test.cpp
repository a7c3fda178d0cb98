// The world's geodetic origin (scene.geodetic_origin, sim/geodetic_origin.h) against
// closed forms: WGS 84's normal gravity, the Earth's rate a resting gyro senses in its
// own axes, the scenario key's defaults and errors, and an SDF world's
// <spherical_coordinates> mapped onto it.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "trackbed/description/sdf_world.h"
#include "trackbed/robot/imu.h"
#include "trackbed/robot/imu_parts.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/geodetic_origin.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// TR8350.2's γe and γp: Somigliana's closed form at 0° and 90°.
TEST(GeodeticOriginTest, NormalGravityAtTheEquatorAndThePolesIsWgs84s) {
  sim::GeodeticOrigin o;
  o.latitude_deg = 0.0;
  EXPECT_NEAR(o.NormalGravity(), 9.7803253359, 1e-6);
  o.latitude_deg = 90.0;
  EXPECT_NEAR(o.NormalGravity(), 9.8321849378, 1e-6);
  o.latitude_deg = -90.0;
  EXPECT_NEAR(o.NormalGravity(), 9.8321849378, 1e-6);
}

// At 45°, against Somigliana's form before simplification,
// (a γe cos²φ + b γp sin²φ) / √(a² cos²φ + b² sin²φ), b = a (1 − f): 9.8061978 m/s².
TEST(GeodeticOriginTest, NormalGravityAt45DegreesIsSomiglianasUnsimplifiedForm) {
  const double a = 6378137.0, b = a * (1.0 - 1.0 / 298.257223563);
  const double ge = 9.7803253359, gp = 9.8321849378;
  const double c2 = 0.5, s2 = 0.5;
  const double expected = (a * ge * c2 + b * gp * s2) / std::sqrt(a * a * c2 + b * b * s2);
  sim::GeodeticOrigin o;
  o.latitude_deg = 45.0;
  EXPECT_NEAR(o.NormalGravity(), expected, 1e-6);
  EXPECT_NEAR(o.NormalGravity(), 9.8061978, 1e-6);
}

// The free-air reduction: −0.3086 mGal/m near the surface (TR8350.2 eq. 4-3's first
// order term, 2γ/a·(1 + f + m − 2f sin²φ)).
TEST(GeodeticOriginTest, NormalGravityFallsWithHeight) {
  sim::GeodeticOrigin o;
  o.latitude_deg = 45.0;
  const double g0 = o.NormalGravity();
  o.elevation_m = 1000.0;
  EXPECT_NEAR((g0 - o.NormalGravity()) / 1000.0, 3.086e-6, 0.002e-6);
}

// A gyro at rest at 48.1° N, the world turned 30° from ENU and the body yawed and
// pitched: it reads ω (cos φ · North + sin φ · Up) in its own axes.
TEST(GeodeticOriginTest, ARestingGyroSensesTheEarthsRateInItsAxes) {
  robot::ImuOptions o = robot::WithImuPartResolved(robot::ImuOptions{}, robot::Realism::kIdeal);
  o.gyro_noise_density = 0.0;
  o.gyro_bias_random_walk = 0.0;
  o.accel_noise_density = 0.0;
  o.accel_bias_random_walk = 0.0;
  o.gyro_initial_bias_std = 0.0;
  o.accel_initial_bias_std = 0.0;
  o.gyro_bias_markov_std = std::vector<double>{};
  o.gyro_bias_markov_tau_s = std::vector<double>{};
  sim::GeodeticOrigin origin;
  origin.latitude_deg = 48.1;
  origin.heading_deg = 30.0;
  // World x = cos 30° E + sin 30° N, y = −sin 30° E + cos 30° N: North is (½, √3/2, 0).
  const Eigen::Vector3d north(0.5, std::sqrt(3.0) / 2.0, 0.0), up(0, 0, 1);
  const double w = 7.292115e-5, phi = 48.1 * kDeg;
  const Eigen::Vector3d expected_world = w * (std::cos(phi) * north + std::sin(phi) * up);
  robot::Imu imu(o, 9.81, 3);
  imu.SetEarthRate(origin.EarthRateInWorld());
  const Eigen::Matrix3d R_world_body = (Eigen::AngleAxisd(70 * kDeg, Eigen::Vector3d::UnitZ()) *
                                        Eigen::AngleAxisd(-8 * kDeg, Eigen::Vector3d::UnitY()))
                                           .toRotationMatrix();
  const robot::ImuSample s =
      imu.Sample(0.01, R_world_body, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const Eigen::Vector3d expected_body = R_world_body.transpose() * expected_world;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.gyro_radps[k], expected_body[k], 1e-9) << k;
  // Upright, the vertical axis reads 15.04°/h · sin φ.
  robot::Imu upright(o, 9.81, 3);
  upright.SetEarthRate(origin.EarthRateInWorld());
  const robot::ImuSample u = upright.Sample(0.01, Eigen::Matrix3d::Identity(),
                                            Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_NEAR(u.gyro_radps.z() / kDeg * 3600.0, 15.041 * std::sin(phi), 1e-3);
  // Without an origin the world does not turn.
  robot::Imu still(o, 9.81, 3);
  EXPECT_EQ(
      still.Sample(0.01, R_world_body, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()).gyro_radps,
      Eigen::Vector3d::Zero());
}

class GeodeticScenarioTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("geodetic_origin_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  scenario::Scenario Parse(const std::string& scene) {
    return scenario::ParseScenario("scene:\n" + scene + "drive: {waypoints: [[0, 0], [1, 0]]}\n",
                                   "s.yaml");
  }
  std::string Error(const std::string& scene) {
    try {
      Parse(scene);
    } catch (const scenario::ScenarioError& e) {
      return e.what();
    }
    return "no error";
  }
  scenario::Scenario LoadWorld(const std::string& world, const std::string& scene_extra = "") {
    std::ofstream(dir_ / "world.sdf") << world;
    std::ofstream(dir_ / "scenario.yaml")
        << "scene:\n  terrain: {extent_m: [-10, -10, 10, 10]}\n  sdf: {file: world.sdf}\n"
        << scene_extra << "drive: {waypoints: [[0, 0], [1, 0]]}\n";
    return scenario::LoadScenario((dir_ / "scenario.yaml").string());
  }
  fs::path dir_;
};

TEST_F(GeodeticScenarioTest, AbsentTheScenarioIsAsBefore) {
  const scenario::Scenario s = Parse("  name: x\n");
  EXPECT_FALSE(s.scene.geodetic_origin);
  EXPECT_EQ(s.scene.world.gravity_mps2, 9.81);
  EXPECT_EQ(scenario::ScenarioToYaml(s).find("geodetic_origin"), std::string::npos);
}

TEST_F(GeodeticScenarioTest, ItsNormalGravityUnlessTheScenarioGivesOne) {
  const std::string origin =
      "  geodetic_origin: {latitude_deg: 48.1, longitude_deg: 11.5, elevation_m: 520, "
      "heading_deg: 30}\n";
  const scenario::Scenario s = Parse(origin);
  ASSERT_TRUE(s.scene.geodetic_origin);
  EXPECT_EQ(s.scene.geodetic_origin->latitude_deg, 48.1);
  EXPECT_EQ(s.scene.geodetic_origin->heading_deg, 30.0);
  EXPECT_EQ(s.scene.world.gravity_mps2, s.scene.geodetic_origin->NormalGravity());
  // 9.8089988 m/s² on the ellipsoid at 48.1°, less 520 m of the free-air gradient.
  EXPECT_NEAR(s.scene.world.gravity_mps2, 9.8073947, 1e-6);
  EXPECT_EQ(Parse(origin + "  world: {gravity_mps2: 9.81}\n").scene.world.gravity_mps2, 9.81);
  // Written and read back: the same keys, the gravity now given.
  const scenario::Scenario again =
      scenario::ParseScenario(scenario::ScenarioToYaml(s), "again.yaml");
  EXPECT_EQ(scenario::ScenarioToYaml(again), scenario::ScenarioToYaml(s));
}

TEST_F(GeodeticScenarioTest, ValuesOutOfRangeAreErrorsNamingTheKey) {
  EXPECT_EQ(Error("  geodetic_origin: {latitude_deg: 91}\n"),
            "s.yaml: scene.geodetic_origin.latitude_deg: must be in [-90, 90] (got 91)");
  EXPECT_EQ(Error("  geodetic_origin: {longitude_deg: -181}\n"),
            "s.yaml: scene.geodetic_origin.longitude_deg: must be in [-180, 180] (got -181)");
  EXPECT_EQ(Error("  geodetic_origin: {elevation_m: 12000}\n"),
            "s.yaml: scene.geodetic_origin.elevation_m: must be in [-11000, 9000] (got 12000)");
  EXPECT_EQ(Error("  geodetic_origin: {heading_deg: .nan}\n"),
            "s.yaml: scene.geodetic_origin.heading_deg: must be in [-360, 360] (got nan)");
  EXPECT_NE(Error("  geodetic_origin: {latitude: 45}\n").find("scene.geodetic_origin.latitude"),
            std::string::npos);
}

constexpr const char* kWorldHead = "<?xml version='1.0'?><sdf version='1.9'><world name='w'>";

TEST_F(GeodeticScenarioTest, SphericalCoordinatesMapOntoTheOrigin) {
  if (!description::CanReadDescriptions()) GTEST_SKIP() << "built without sdformat";
  const std::string sc =
      "<spherical_coordinates><surface_model>EARTH_WGS84</surface_model>"
      "<world_frame_orientation>ENU</world_frame_orientation><latitude_deg>48.1</latitude_deg>"
      "<longitude_deg>11.5</longitude_deg><elevation>520</elevation>"
      "<heading_deg>30</heading_deg></spherical_coordinates>";
  const scenario::Scenario s = LoadWorld(kWorldHead + sc + "</world></sdf>");
  ASSERT_TRUE(s.scene.geodetic_origin);
  EXPECT_NEAR(s.scene.geodetic_origin->latitude_deg, 48.1, 1e-12);
  EXPECT_NEAR(s.scene.geodetic_origin->longitude_deg, 11.5, 1e-12);
  EXPECT_EQ(s.scene.geodetic_origin->elevation_m, 520.0);
  EXPECT_NEAR(s.scene.geodetic_origin->heading_deg, 30.0, 1e-12);
  // No <gravity> in the world and none in the scenario: the origin's normal gravity.
  EXPECT_EQ(s.scene.world.gravity_mps2, s.scene.geodetic_origin->NormalGravity());
  for (const std::string& u : s.scene.sdf->unmapped) {
    EXPECT_EQ(u.find("spherical_coordinates"), std::string::npos) << u;
  }
  // The world's <gravity> wins, then the scenario's.
  EXPECT_EQ(
      LoadWorld(kWorldHead + std::string("<gravity>0 0 -9.79</gravity>") + sc + "</world></sdf>")
          .scene.world.gravity_mps2,
      9.79);
  EXPECT_EQ(LoadWorld(kWorldHead + sc + "</world></sdf>", "  world: {gravity_mps2: 9.81}\n")
                .scene.world.gravity_mps2,
            9.81);
  // Without <spherical_coordinates>: no origin, sdformat's default gravity as before.
  const scenario::Scenario plain = LoadWorld(kWorldHead + std::string("</world></sdf>"));
  EXPECT_FALSE(plain.scene.geodetic_origin);
  EXPECT_EQ(plain.scene.world.gravity_mps2, 9.8);
}

TEST_F(GeodeticScenarioTest, WhatTheOriginCannotHonourIsAnError) {
  if (!description::CanReadDescriptions()) GTEST_SKIP() << "built without sdformat";
  const auto error = [this](const std::string& sc) -> std::string {
    try {
      LoadWorld(kWorldHead + ("<spherical_coordinates>" + sc + "</spherical_coordinates>") +
                "</world></sdf>");
    } catch (const scenario::ScenarioError& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string ned =
      error("<world_frame_orientation>NED</world_frame_orientation><latitude_deg>1</latitude_deg>");
  EXPECT_NE(ned.find("scene.sdf.file"), std::string::npos) << ned;
  EXPECT_NE(ned.find("<world_frame_orientation> [NED] is not supported"), std::string::npos) << ned;
  const std::string moon =
      error("<surface_model>MOON_SCS</surface_model><latitude_deg>1</latitude_deg>");
  EXPECT_NE(moon.find("<surface_model> [MOON_SCS] is not supported"), std::string::npos) << moon;
  const std::string lat = error("<latitude_deg>148</latitude_deg>");
  EXPECT_NE(lat.find("maps onto scene.geodetic_origin.latitude_deg: must be in [-90, 90]"),
            std::string::npos)
      << lat;
}

}  // namespace
}  // namespace trackbed
