// SDF worlds written here, read through sdformat and mapped onto the scene
// (docs/gazebo_users.md): each shape where the world puts it, what is not mapped
// listed, errors naming the file and the element.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "trackbed/assets/heightmap_reader.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/description/sdf_world.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/triangle_mesh.h"
#include "trackbed/sim/world.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

void Write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

class SdfWorldTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!description::CanReadDescriptions()) {
      GTEST_SKIP() << "built without sdformat (TRACKBED_WITH_SDF=OFF)";
    }
    dir_ = fs::temp_directory_path() / ("sdf_world_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // A crate model found through model://: a 1 m cube as an OBJ, its origin at its base.
    Write(dir_ / "models/crate/model.config",
          "<?xml version='1.0'?><model><name>crate</name><sdf version='1.9'>model.sdf</sdf>"
          "</model>\n");
    Write(dir_ / "models/crate/model.sdf", R"(<?xml version='1.0'?>
<sdf version='1.9'><model name='crate'><static>true</static><link name='body'>
  <visual name='v'><geometry><mesh><uri>model://crate/meshes/crate.obj</uri></mesh></geometry></visual>
  <collision name='c'><geometry><mesh><uri>model://crate/meshes/crate.obj</uri></mesh></geometry></collision>
</link></model></sdf>
)");
    Write(dir_ / "models/crate/meshes/crate.obj",
          "v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0.5 0.5 0\nv -0.5 0.5 0\n"
          "v -0.5 -0.5 1\nv 0.5 -0.5 1\nv 0.5 0.5 1\nv -0.5 0.5 1\n"
          "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
          "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n");
    // The heightmap: 33 × 33 pixels of 16 bits, rising along x and towards the image's
    // foot; the ball's albedo map: 2 × 2 texels of sRGB colours.
    cv::Mat hill(33, 33, CV_16UC1);
    for (int r = 0; r < 33; ++r) {
      for (int c = 0; c < 33; ++c) hill.at<std::uint16_t>(r, c) = HillValue(c, r);
    }
    cv::imwrite((dir_ / "hill.png").string(), hill);
    cv::Mat map(2, 2, CV_8UC3);
    map.at<cv::Vec3b>(0, 0) = {0, 0, 255};  // blue, green, red: red
    map.at<cv::Vec3b>(0, 1) = {0, 255, 0};
    map.at<cv::Vec3b>(1, 0) = {255, 0, 0};
    map.at<cv::Vec3b>(1, 1) = {128, 128, 128};
    cv::imwrite((dir_ / "ball_albedo.png").string(), map);
  }
  static int HillValue(int c, int r) { return 1000 + 1500 * c + 400 * r; }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  // A scenario naming `world` (written as world.sdf) with the models folder.
  scenario::Scenario Load(const std::string& world) {
    Write(dir_ / "world.sdf", world);
    Write(dir_ / "scenario.yaml",
          "scene:\n  terrain: {extent_m: [-10, -10, 10, 10]}\n"
          "  sdf: {file: world.sdf, model_paths: [models]}\n"
          "drive: {waypoints: [[0, 0], [1, 0]]}\n");
    return scenario::LoadScenario((dir_ / "scenario.yaml").string());
  }

  fs::path dir_;
};

// A world with every kind of thing the mapping meets.
const char* kWorld = R"(<?xml version='1.0'?>
<sdf version='1.9'>
<world name='yard'>
  <physics name='fast' type='ode'><max_step_size>0.002</max_step_size></physics>
  <gravity>0 0 -9.8</gravity>
  <light type='directional' name='sun'><direction>-0.5 0.1 -0.9</direction></light>
  <light type='point' name='lamp'><pose>0 0 3 0 0 0</pose></light>
  <spherical_coordinates><latitude_deg>45</latitude_deg></spherical_coordinates>
  <plugin filename='gz-sim-physics-system' name='gz::sim::systems::Physics'/>
  <model name='ground_plane'><static>true</static><link name='link'>
    <collision name='c'><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
      <surface><friction><ode><mu>0.5</mu></ode></friction></surface></collision>
    <visual name='v'><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></visual>
  </link></model>
  <frame name='yard_corner'><pose>2 1 0 0 0 1.5707963267948966</pose></frame>
  <model name='box'><static>true</static><pose relative_to='yard_corner'>1 0 0.5 0 0 0</pose>
    <link name='l'>
      <visual name='v'><geometry><box><size>2 1 1</size></box></geometry>
        <material><diffuse>0.8 0.1 0.1 1</diffuse></material></visual>
      <collision name='c'><geometry><box><size>2 1 1</size></box></geometry>
        <surface><friction><ode><mu>0.9</mu></ode></friction></surface></collision>
    </link></model>
  <model name='log'><static>true</static><pose>-3 2 0.3 1.5707963267948966 0 0</pose>
    <link name='l'>
      <visual name='v'><geometry><cylinder><radius>0.3</radius><length>2</length></cylinder></geometry></visual>
      <collision name='c'><geometry><cylinder><radius>0.3</radius><length>2</length></cylinder></geometry></collision>
    </link></model>
  <model name='post'><static>true</static><pose>4 -4 1 0 0 0</pose>
    <link name='l'><pose>0 0 0.5 0 0 0</pose>
      <visual name='v'><geometry><cylinder><radius>0.1</radius><length>3</length></cylinder></geometry></visual>
      <collision name='c'><geometry><cylinder><radius>0.1</radius><length>3</length></cylinder></geometry></collision>
    </link></model>
  <model name='ball'><static>true</static><pose>-2 -3 0.4 0 0 0</pose>
    <link name='l'>
      <visual name='v'><geometry><ellipsoid><radii>0.4 0.4 0.4</radii></ellipsoid></geometry>
        <material><pbr><metal><albedo_map>ball_albedo.png</albedo_map>
          <normal_map>ball_normal.png</normal_map></metal></pbr></material></visual>
      <collision name='c'><geometry><ellipsoid><radii>0.4 0.4 0.4</radii></ellipsoid></geometry></collision>
    </link></model>
  <include><uri>model://crate</uri><pose>5 3 0 0 0 0.5</pose></include>
  <model name='hill'><static>true</static><pose>1 -1 0.5 0 0 0</pose><link name='l'>
    <visual name='v'><geometry><heightmap><uri>hill.png</uri><size>24 24 2</size>
      <pos>0 0 -0.5</pos></heightmap></geometry></visual>
    <collision name='c'><geometry><heightmap><uri>hill.png</uri><size>24 24 2</size>
      <pos>0 0 -0.5</pos></heightmap></geometry></collision>
  </link></model>
  <model name='cart'><pose>0 5 0.2 0 0 0</pose><link name='l'>
    <visual name='v'><geometry><box><size>1 1 0.4</size></box></geometry></visual></link></model>
</world>
</sdf>
)";

TEST_F(SdfWorldTest, EachShapeWhereTheWorldPutsIt) {
  const scenario::Scenario s = Load(kWorld);
  const std::vector<sim::StaticObject>& objects = s.scene.objects;
  ASSERT_EQ(objects.size(), 5u);
  // The box: its frame's pose composed through relative_to (yard_corner turned 90°).
  const sim::StaticObject& box = objects[0];
  EXPECT_EQ(box.shape, sim::StaticObject::Shape::kBox);
  EXPECT_NEAR(box.center_m.x(), 2.0, 1e-12);
  EXPECT_NEAR(box.center_m.y(), 2.0, 1e-12);
  EXPECT_NEAR(box.base_z_m, 0.0, 1e-12);
  EXPECT_NEAR(box.yaw_rad, kPi / 2, 1e-12);
  EXPECT_EQ(box.size_m, Eigen::Vector3d(2, 1, 1));
  EXPECT_TRUE(box.collides);
  // The log: a cylinder lying along y, as the unit cylinder's mesh scaled and turned.
  const sim::StaticObject& log = objects[1];
  EXPECT_EQ(log.shape, sim::StaticObject::Shape::kMesh);
  EXPECT_EQ(fs::path(log.mesh.file).filename(), "unit_cylinder.ply");
  EXPECT_EQ(log.mesh.scale, Eigen::Vector3d(0.3, 0.3, 2.0));
  EXPECT_NEAR(log.roll_rad, kPi / 2, 1e-12);
  EXPECT_NEAR(log.center_m.x(), -3.0, 1e-12);
  EXPECT_NEAR(log.base_z_m, 0.3, 1e-12);
  // Its triangles placed: the log spans y 1..3 and z 0..0.6 (the facets' chords inside).
  const assets::SceneMeshes meshes = assets::LoadSceneMeshes({log});
  const sim::PlacedMesh placed(*meshes.obstacles[0].visual, log.mesh.scale,
                               meshes.obstacles[0].Pose());
  EXPECT_NEAR(placed.bounds().min().y(), 1.0, 1e-9);
  EXPECT_NEAR(placed.bounds().max().y(), 3.0, 1e-9);
  EXPECT_NEAR(placed.bounds().min().z(), 0.0, 1e-9);
  EXPECT_NEAR(placed.bounds().max().z(), 0.6, 1e-9);
  EXPECT_NEAR(placed.bounds().min().x(), -3.3, 1e-9);
  // The post: upright, its link's pose on top of the model's.
  const sim::StaticObject& post = objects[2];
  EXPECT_EQ(post.shape, sim::StaticObject::Shape::kCylinder);
  EXPECT_EQ(post.center_m, Eigen::Vector2d(4, -4));
  EXPECT_NEAR(post.base_z_m, 0.0, 1e-12);
  EXPECT_EQ(post.radius_m, 0.1);
  EXPECT_EQ(post.height_m, 3.0);
  // The ball (an ellipsoid of equal radii): the unit sphere scaled by its radii,
  // centred where the model is.
  const sim::StaticObject& ball = objects[3];
  EXPECT_EQ(fs::path(ball.mesh.file).filename(), "unit_sphere.ply");
  EXPECT_EQ(ball.mesh.scale, Eigen::Vector3d::Constant(0.4));
  EXPECT_EQ(ball.center_m, Eigen::Vector2d(-2, -3));
  EXPECT_NEAR(ball.base_z_m, 0.4, 1e-12);
  // The crate, included through model://: its OBJ file, turned by the include's yaw.
  const sim::StaticObject& crate = objects[4];
  EXPECT_EQ(crate.mesh.file, (dir_ / "models/crate/meshes/crate.obj").string());
  EXPECT_EQ(crate.center_m, Eigen::Vector2d(5, 3));
  EXPECT_NEAR(crate.yaw_rad, 0.5, 1e-12);
  EXPECT_EQ(crate.mesh.collision, sim::MeshSource::Collision::kMesh);
  EXPECT_TRUE(crate.collides);
}

// Bullet's ray tests (what the range sensor casts and the hull collides with) meet each
// mapped solid where the world puts its surface.
TEST_F(SdfWorldTest, RaysMeetEachSolidWhereTheWorldPutsIt) {
  const scenario::Scenario s = Load(kWorld);
  const assets::SceneMeshes meshes = assets::LoadSceneMeshes(s.scene.objects);
  const sim::World world(s.scene.world, sim::Terrain(s.scene.terrain, 1), meshes.primitives,
                         meshes.obstacles);
  const auto hit = [&world](Eigen::Vector3d from, Eigen::Vector3d to) {
    const std::optional<sim::RayHit> h = world.CastRay(from, to, sim::kGroupObstacle);
    return h ? h->point_world : Eigen::Vector3d::Constant(std::nan(""));
  };
  // The box, turned 90°: its 2 m along y, so its face towards −y at y = 1.
  EXPECT_NEAR(hit({2, -5, 0.5}, {2, 5, 0.5}).y(), 1.0, 1e-6);
  // The lying log (radius 0.3 about the line x = −3, z = 0.3): a facet's vertex at x = −3.3.
  EXPECT_NEAR(hit({-6, 2, 0.3}, {0, 2, 0.3}).x(), -3.3, 1e-6);
  // The ball (radius 0.4 at (−2, −3, 0.4)): a vertex of its equator at y = −3.4.
  EXPECT_NEAR(hit({-2, -6, 0.4}, {-2, 0, 0.4}).y(), -3.4, 1e-6);
  // The post (radius 0.1 at (4, −4)), from 0 to 3 m high.
  EXPECT_NEAR(hit({4, -8, 1}, {4, 0, 1}).y(), -4.1, 1e-6);
  EXPECT_TRUE(std::isnan(hit({4, -8, 3.1}, {4, 0, 3.1}).y()));
  // The crate (a 1 m cube through model://): its top at z = 1.
  EXPECT_NEAR(hit({5, 3, 5}, {5, 3, -1}).z(), 1.0, 1e-6);
}

TEST_F(SdfWorldTest, PhysicsSunAndGroundFrictionMapped) {
  const scenario::Scenario s = Load(kWorld);
  EXPECT_EQ(s.scene.world.physics_step_s, 0.002);
  EXPECT_EQ(s.scene.world.gravity_mps2, 9.8);  // the world's <gravity> wins over the origin's
  ASSERT_TRUE(s.scene.geodetic_origin);
  EXPECT_EQ(s.scene.geodetic_origin->latitude_deg, 45.0);
  EXPECT_NEAR(s.scene.appearance.sun_azimuth_deg, std::atan2(-0.1, 0.5) * 180 / kPi, 1e-12);
  EXPECT_NEAR(s.scene.appearance.sun_elevation_deg,
              std::asin(0.9 / std::sqrt(0.25 + 0.01 + 0.81)) * 180 / kPi, 1e-12);
  // μ 0.5: the built-in material whose tan φ is nearest.
  double best = 1e9;
  std::string nearest;
  for (const sim::TerrainMaterial& m : sim::BuiltinMaterials()) {
    const double d = std::abs(std::tan(m.friction_angle_deg * kPi / 180) - 0.5);
    if (d < best) best = d, nearest = m.name;
  }
  EXPECT_EQ(s.scene.terrain.default_material, nearest);
}

TEST_F(SdfWorldTest, WhatIsNotMappedIsListed) {
  const scenario::Scenario s = Load(kWorld);
  ASSERT_TRUE(s.scene.sdf && s.scene.sdf->mapped);
  const std::vector<std::string>& u = s.scene.sdf->unmapped;
  const auto listed = [&u](const std::string& part) {
    for (const std::string& entry : u) {
      if (entry.find(part) != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_TRUE(listed("<plugin>") || listed("/plugin")) << ::testing::PrintToString(u);
  EXPECT_FALSE(listed("spherical_coordinates"));  // mapped: scene.geodetic_origin
  EXPECT_TRUE(listed("only the sun"));
  EXPECT_TRUE(listed("not static"));
  EXPECT_TRUE(listed("<normal_map>"));
  EXPECT_TRUE(listed("its mean grey albedo"));
  EXPECT_TRUE(listed("mu 0.9"));
  // Each entry names the world's file.
  for (const std::string& entry : u) EXPECT_NE(entry.find("world.sdf"), std::string::npos) << entry;
}

// The heightmap is the terrain: each pixel's height where Gazebo puts it (the image
// centred on the model's pose plus <pos>, its top row at +y, the brightest pixel
// <size>'s z above black), bilinear between pixels.
TEST_F(SdfWorldTest, TheHeightmapIsTheTerrainWithEachPixelWhereGazeboPutsIt) {
  const scenario::Scenario s = Load(kWorld);
  ASSERT_TRUE(s.scene.terrain.heightmap);
  const sim::HeightmapOptions& h = *s.scene.terrain.heightmap;
  EXPECT_EQ(h.file, (dir_ / "hill.png").string());
  EXPECT_EQ(h.size_m, Eigen::Vector3d(24, 24, 2));
  EXPECT_EQ(h.pos_m, Eigen::Vector3d(1, -1, 0));
  const auto grid = assets::ReadHeightmap(h);
  const sim::Terrain terrain(s.scene.terrain, 1, grid);
  const double brightest = HillValue(32, 32);
  double worst = 0.0;
  for (int r = 4; r <= 28; r += 4) {
    for (int c = 4; c <= 28; c += 4) {
      // Pixel (c, r) on one of the terrain's grid points (0.75 m pixels, 0.1 m cells).
      const double x = 1 - 12 + 0.75 * c, y = -1 + 12 - 0.75 * r;
      const double z = 2.0 * HillValue(c, r) / brightest;
      EXPECT_NEAR(grid->Height(x, y), z, 1e-12) << c << ", " << r;
      worst = std::max(worst, std::abs(terrain.Height(x, y) - z));
      // Halfway between four pixels: their mean.
      const double mean =
          2.0 *
          (HillValue(c, r) + HillValue(c + 1, r) + HillValue(c, r + 1) + HillValue(c + 1, r + 1)) /
          (4 * brightest);
      EXPECT_NEAR(grid->Height(x + 0.375, y - 0.375), mean, 1e-12);
    }
  }
  std::printf("the terrain's heights at 49 pixel centres: worst error %.3g m\n", worst);
  EXPECT_LT(worst, 1e-5);  // the terrain's grid holds single-precision heights
  // A heightmap short of the terrain is an error naming the key.
  std::string yaml = scenario::ScenarioToYaml(s);
  Write(dir_ / "short.yaml", yaml);
  EXPECT_THROW(scenario::LoadScenario((dir_ / "short.yaml").string(),
                                      {{"scene.terrain.extent_m", "[-20, -10, 10, 10]"}}),
               scenario::ScenarioError);
}

// The new keys' errors name the file, the key and the problem.
TEST_F(SdfWorldTest, HeightmapAndAlbedoKeysErrorsNameTheKey) {
  const auto error_of = [this](const std::string& scene) {
    Write(dir_ / "keys.yaml", "scene:\n" + scene + "drive: {waypoints: [[0, 0], [1, 0]]}\n");
    try {
      scenario::LoadScenario((dir_ / "keys.yaml").string());
    } catch (const scenario::ScenarioError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string terrain = "  terrain: {extent_m: [-10, -10, 10, 10], heightmap: ";
  std::string e = error_of(terrain + "{file: hill.png, size_m: [24, 0, 2]}}\n");
  EXPECT_NE(e.find("keys.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("scene.terrain.heightmap.size_m"), std::string::npos) << e;
  e = error_of(terrain + "{file: nowhere.png, size_m: [24, 24, 2]}}\n");
  EXPECT_NE(e.find("scene.terrain.heightmap.file"), std::string::npos) << e;
  EXPECT_NE(e.find("nowhere.png"), std::string::npos) << e;
  e = error_of(terrain + "{file: ball_albedo.png, size_m: [24, 24, 2]}}\n");  // colour, 2 × 2
  EXPECT_NE(e.find("scene.terrain.heightmap.file"), std::string::npos) << e;
  EXPECT_NE(e.find("channels"), std::string::npos) << e;
  e = error_of(terrain + "{file: hill.png, size_m: [24, 24, 2]}, dem: {file: hill.png}}\n");
  EXPECT_NE(e.find("scene.terrain.heightmap"), std::string::npos) << e;
  EXPECT_NE(e.find("exclude each other"), std::string::npos) << e;
  e = error_of("  objects: [{type: box, albedo: 1.5}]\n");
  EXPECT_NE(e.find("scene.objects[0].albedo"), std::string::npos) << e;
  EXPECT_NE(e.find("[0, 1]"), std::string::npos) << e;
  // Given, an albedo is written back; absent, it stays absent.
  const scenario::Scenario back = scenario::ParseScenario(
      scenario::ScenarioToYaml(scenario::ParseScenario(
          "scene: {objects: [{albedo: 0.25}, {}]}\ndrive: {waypoints: [[0, 0], [1, 0]]}\n",
          "inline")),
      "written");
  ASSERT_EQ(back.scene.objects.size(), 2u);
  EXPECT_EQ(back.scene.objects[0].albedo, std::optional<double>(0.25));
  EXPECT_FALSE(back.scene.objects[1].albedo);
}

TEST_F(SdfWorldTest, ColoursAreGreyAlbedos) {
  const scenario::Scenario s = Load(kWorld);
  // The box's <diffuse> (0.8, 0.1, 0.1): Rec. 709 luma of the linear colour.
  ASSERT_TRUE(s.scene.objects[0].albedo);
  EXPECT_NEAR(*s.scene.objects[0].albedo, 0.2126 * 0.8 + 0.7152 * 0.1 + 0.0722 * 0.1, 1e-7);
  // The ball's albedo map (an ellipsoid's, which Gazebo's mesh gives no texture
  // coordinates): the mean of its texels' luma, sRGB decoded.
  const auto linear = [](double e) {
    return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
  };
  const double grey = linear(128.0 / 255.0);
  const double expected = (0.2126 + 0.7152 + 0.0722 + grey) / 4;
  ASSERT_TRUE(s.scene.objects[3].albedo);
  EXPECT_NEAR(*s.scene.objects[3].albedo, expected, 1e-12);
  EXPECT_FALSE(s.scene.objects[1].albedo);  // the log has no material: today's look
}

TEST_F(SdfWorldTest, MappedScenarioReadsBackWithoutMappingAgain) {
  const scenario::Scenario s = Load(kWorld);
  const std::string yaml = scenario::ScenarioToYaml(s);
  const scenario::Scenario again = scenario::ParseScenario(yaml, "resolved");
  EXPECT_EQ(again.scene.objects.size(), s.scene.objects.size());
  EXPECT_EQ(scenario::ScenarioToYaml(again), yaml);
  Write(dir_ / "resolved.yaml", yaml);
  EXPECT_EQ(scenario::LoadScenario((dir_ / "resolved.yaml").string()).scene.objects.size(),
            s.scene.objects.size());
}

// The message of the ScenarioError loading `world` throws.
std::string ErrorOf(SdfWorldTest* t, const std::function<void()>& load) {
  (void)t;
  try {
    load();
  } catch (const scenario::ScenarioError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST_F(SdfWorldTest, ErrorsNameTheFileAndTheElement) {
  // Malformed: a box without its size's numbers.
  std::string e = ErrorOf(this, [this] {
    Load(
        "<?xml version='1.0'?><sdf version='1.9'><world name='w'><model name='m'><link name='l'>"
        "<visual name='v'><geometry><box><size>1 x</size></box></geometry></visual>"
        "</link></model></world></sdf>");
  });
  EXPECT_NE(e.find("scene.sdf.file"), std::string::npos) << e;
  EXPECT_NE(e.find("world.sdf"), std::string::npos) << e;
  EXPECT_NE(e.find("size"), std::string::npos) << e;
  // A model:// URI in none of the paths.
  e = ErrorOf(this, [this] {
    Load(
        "<?xml version='1.0'?><sdf version='1.9'><world name='w'><model name='m'>"
        "<static>true</static><link name='l'><visual name='v'><geometry><mesh>"
        "<uri>model://nowhere/a.obj</uri></mesh></geometry></visual></link></model></world></sdf>");
  });
  EXPECT_NE(e.find("model://nowhere/a.obj"), std::string::npos) << e;
  EXPECT_NE(e.find("visual[@name=\"v\"]"), std::string::npos) << e;
  // A Fuel URL, refused by name.
  e = ErrorOf(this, [this] {
    Load(
        "<?xml version='1.0'?><sdf version='1.9'><world name='w'><include><uri>"
        "https://fuel.gazebosim.org/1.0/OpenRobotics/models/Oak tree</uri></include>"
        "</world></sdf>");
  });
  EXPECT_NE(e.find("Fuel"), std::string::npos) << e;
  EXPECT_NE(e.find("https://fuel.gazebosim.org"), std::string::npos) << e;
  // Not XML at all.
  e = ErrorOf(this, [this] { Load("this is not a world"); });
  EXPECT_NE(e.find("world.sdf"), std::string::npos) << e;
}

}  // namespace
}  // namespace trackbed
