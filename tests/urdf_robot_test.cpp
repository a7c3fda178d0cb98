// URDF robots written here, read through urdfdom and mapped onto the vehicle and the
// stereo camera's mount (docs/gazebo_users.md, "A robot in URDF").
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "trackbed/common/archive.h"
#include "trackbed/description/urdf_robot.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed {
namespace {

namespace fs = std::filesystem;

// A link with a wheel's cylinder (turned so its axis lies along y) and a mass.
std::string WheelLink(const std::string& name, double radius, double width, double mass) {
  const std::string cyl = "<geometry><cylinder radius='" + std::to_string(radius) + "' length='" +
                          std::to_string(width) + "'/></geometry>";
  return "<link name='" + name + "'><inertial><mass value='" + std::to_string(mass) +
         "'/><inertia ixx='0.01' ixy='0' ixz='0' iyy='0.01' iyz='0' izz='0.01'/></inertial>"
         "<visual><origin rpy='1.5707963267948966 0 0'/>" +
         cyl +
         "</visual>"
         "<collision><origin rpy='1.5707963267948966 0 0'/>" +
         cyl + "</collision></link>\n";
}

std::string TurningJoint(const std::string& name, const std::string& child, double x, double y,
                         double z) {
  return "<joint name='" + name + "' type='continuous'><parent link='base_link'/><child link='" +
         child + "'/><origin xyz='" + std::to_string(x) + " " + std::to_string(y) + " " +
         std::to_string(z) + "'/><axis xyz='0 1 0'/></joint>\n";
}

// Four wheels at x ±0.2, y ±0.25 under a 20 kg chassis box 5 cm above base_link; a camera
// 0.25 m ahead and 0.15 m above the chassis's centre, pitched 0.2 rad down; an IMU.
std::string SkidSteer() {
  std::string u =
      "<?xml version='1.0'?>\n<robot name='skid4'>\n<link name='base_link'/>\n"
      "<link name='chassis_link'><inertial><mass value='20'/>"
      "<inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial>"
      "<collision><geometry><box size='0.6 0.4 0.2'/></geometry></collision></link>\n"
      "<joint name='chassis_joint' type='fixed'><parent link='base_link'/>"
      "<child link='chassis_link'/><origin xyz='0 0 0.05'/></joint>\n";
  const char* names[] = {"front_left_wheel", "front_right_wheel", "rear_left_wheel",
                         "rear_right_wheel"};
  for (int k = 0; k < 4; ++k) {
    u += WheelLink(names[k], 0.1, 0.06, 1.0);
    u += TurningJoint(std::string(names[k]) + "_joint", names[k], k < 2 ? 0.2 : -0.2,
                      k % 2 == 0 ? 0.25 : -0.25, 0.0);
  }
  u += "<link name='camera_link'/><joint name='camera_joint' type='fixed'>"
       "<parent link='chassis_link'/><child link='camera_link'/>"
       "<origin xyz='0.25 0 0.15' rpy='0 0.2 0'/></joint>\n"
       "<link name='camera_optical_frame'/><joint name='camera_optical_joint' type='fixed'>"
       "<parent link='camera_link'/><child link='camera_optical_frame'/>"
       "<origin rpy='-1.5707963267948966 0 -1.5707963267948966'/></joint>\n"
       "<link name='imu_link'/><joint name='imu_joint' type='fixed'><parent link='base_link'/>"
       "<child link='imu_link'/><origin xyz='0.1 0 0.1'/></joint>\n</robot>\n";
  return u;
}

class UrdfRobotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!description::CanReadDescriptions()) {
      GTEST_SKIP() << "built without urdfdom (TRACKBED_WITH_SDF=OFF)";
    }
    dir_ = fs::temp_directory_path() / ("urdf_robot_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  scenario::Scenario Load(const std::string& urdf, const std::string& name = "robot.urdf") {
    std::ofstream(dir_ / name) << urdf;
    std::ofstream(dir_ / "scenario.yaml")
        << "robot:\n  description: {file: " << name << "}\n  stereo: {enabled: true}\n"
        << "drive: {waypoints: [[0, 0], [1, 0]]}\n";
    return scenario::LoadScenario((dir_ / "scenario.yaml").string());
  }
  std::string ErrorOf(const std::string& urdf, const std::string& name = "robot.urdf") {
    try {
      Load(urdf, name);
    } catch (const scenario::ScenarioError& e) {
      return e.what();
    }
    return "(no error)";
  }
  fs::path dir_;
};

TEST_F(UrdfRobotTest, FourWheelSkidSteerWithCamera) {
  const scenario::Scenario s = Load(SkidSteer());
  const robot::TrackedVehicleOptions& v = s.robot.vehicle;
  // Mass 24 kg; centre of mass (20 · 0.05) / 24 m above base_link; the ground 0.1 m below.
  // Each value is rounded to 1e-9 of its unit.
  const double com_z = 20.0 * 0.05 / 24.0;
  EXPECT_NEAR(v.mass_kg, 24.0, 5e-10);
  EXPECT_NEAR(v.com_height_m, com_z + 0.1, 5e-10);
  EXPECT_NEAR(v.ground_clearance_m, 0.05 - 0.1 + 0.1, 5e-10);
  EXPECT_EQ(v.hull_size_m, Eigen::Vector3d(0.6, 0.4, 0.2));
  EXPECT_NEAR(v.track_gauge_m, 0.5, 5e-10);
  EXPECT_NEAR(v.sprocket_radius_m, 0.1, 5e-10);
  EXPECT_NEAR(v.track_width_m, 0.06, 5e-10);
  ASSERT_EQ(v.station_x_m.size(), 2u);
  EXPECT_NEAR(v.station_x_m[0], -0.2, 5e-10);
  EXPECT_NEAR(v.station_x_m[1], 0.2, 5e-10);
  EXPECT_EQ(v.contact, robot::TrackedVehicleOptions::Contact::kWheels);
  // The camera: its joint's origin from the centre of mass, its pitch.
  EXPECT_NEAR(s.robot.stereo.mount_m.x(), 0.25, 5e-10);
  EXPECT_NEAR(s.robot.stereo.mount_m.y(), 0.0, 5e-10);
  EXPECT_NEAR(s.robot.stereo.mount_m.z(), 0.05 + 0.15 - com_z, 5e-10);
  EXPECT_NEAR(s.robot.stereo.pitch_down_deg, 0.2 * 180 / 3.14159265358979323846, 1e-9);
  // Said: the inertia tensors and the IMU's mount.
  ASSERT_TRUE(s.robot.description && s.robot.description->mapped);
  const std::vector<std::string>& u = s.robot.description->unmapped;
  ASSERT_EQ(u.size(), 2u) << ::testing::PrintToString(u);
  EXPECT_NE(u[0].find("inertia"), std::string::npos);
  EXPECT_NE(u[1].find("imu_link"), std::string::npos);
  // Written and read back: mapped once.
  const std::string yaml = scenario::ScenarioToYaml(s);
  EXPECT_EQ(scenario::ScenarioToYaml(scenario::ParseScenario(yaml, "resolved")), yaml);
}

// The skid-steer robot with Gazebo's sensor blocks on its links: a multicamera pair
// (a stereo head) on the camera link, 0.1 m apart along the link's y, and a lidar on
// a mast; an IMU block and a camera's distortion, which have no key, listed.
std::string SkidSteerWithSensorBlocks() {
  std::string u = SkidSteer();
  u.insert(u.rfind("</robot>"), R"(
<link name='mast_link'/><joint name='mast_joint' type='fixed'><parent link='chassis_link'/>
  <child link='mast_link'/><origin xyz='-0.1 0 0.3'/></joint>
<gazebo reference='camera_link'>
  <sensor type='multicamera' name='stereo_head'>
    <update_rate>15</update_rate>
    <camera name='left'><pose>0 0.05 0 0 0 0</pose><horizontal_fov>1.2</horizontal_fov>
      <image><width>752</width><height>480</height><format>L8</format></image>
      <clip><near>0.1</near><far>60</far></clip>
      <noise><type>gaussian</type><mean>0</mean><stddev>0.007</stddev></noise>
      <distortion><k1>-0.28</k1><k2>0.07</k2></distortion></camera>
    <camera name='right'><pose>0 -0.05 0 0 0 0</pose><horizontal_fov>1.2</horizontal_fov>
      <image><width>752</width><height>480</height><format>L8</format></image>
      <clip><near>0.1</near><far>60</far></clip></camera>
  </sensor>
</gazebo>
<gazebo reference='mast_link'>
  <sensor type='ray' name='scanner'><pose>0 0 0.05 0 0 0</pose><update_rate>20</update_rate>
    <ray><scan><horizontal><samples>270</samples><resolution>1</resolution>
      <min_angle>-2.35619449</min_angle><max_angle>2.35619449</max_angle></horizontal></scan>
      <range><min>0.12</min><max>12</max><resolution>0.01</resolution></range>
      <noise><type>gaussian</type><mean>0</mean><stddev>0.015</stddev></noise></ray>
  </sensor>
</gazebo>
<gazebo reference='imu_link'><sensor type='imu' name='imu'/></gazebo>
)");
  return u;
}

TEST_F(UrdfRobotTest, SensorBlocksMapOntoTheStereoPairAndTheRangeSensor) {
  const scenario::Scenario s = Load(SkidSteerWithSensorBlocks());
  const double com_z = 20.0 * 0.05 / 24.0;
  const robot::StereoRigOptions& st = s.robot.stereo;
  EXPECT_EQ(st.width_px, 752);
  EXPECT_EQ(st.height_px, 480);
  EXPECT_NEAR(st.hfov_deg, 1.2 * 180 / 3.14159265358979323846, 1e-9);
  EXPECT_EQ(st.rate_hz, 15.0);
  EXPECT_EQ(st.near_m, 0.1);
  EXPECT_EQ(st.far_m, 60.0);
  EXPECT_NEAR(st.noise_std, 0.007 * 255, 1e-12);
  EXPECT_NEAR(st.baseline_m, 0.1, 5e-10);
  // The pair's midpoint is the camera link's origin; its pitch the link's.
  EXPECT_NEAR(st.mount_m.x(), 0.25, 5e-10);
  EXPECT_NEAR(st.mount_m.y(), 0.0, 5e-10);
  EXPECT_NEAR(st.mount_m.z(), 0.05 + 0.15 - com_z, 5e-10);
  EXPECT_NEAR(st.pitch_down_deg, 0.2 * 180 / 3.14159265358979323846, 1e-9);
  // The focal length from the field of view: (752 / 2) / tan(0.6).
  EXPECT_NEAR(st.DesignIntrinsics().fx, 376.0 / std::tan(0.6), 1e-6);
  const robot::RangeSensorOptions& r = s.robot.range_sensor;
  // 270 samples over 270 deg, both ends included: 360 deg at the same spacing.
  EXPECT_EQ(r.beams,
            static_cast<int>(std::lround(2 * 3.14159265358979323846 * 269 / (2 * 2.35619449))));
  EXPECT_EQ(r.rate_hz, 20.0);
  EXPECT_EQ(r.min_range_m, 0.12);
  EXPECT_EQ(r.max_range_m, 12.0);
  EXPECT_EQ(r.noise_std_m, 0.015);
  EXPECT_NEAR(r.mount_m.x(), -0.1, 5e-10);
  EXPECT_NEAR(r.mount_m.z(), 0.05 + 0.3 + 0.05 - com_z, 5e-10);
  // What has no key is listed, naming the file and the block.
  const std::vector<std::string>& u = s.robot.description->unmapped;
  const auto listed = [&u](const std::string& a, const std::string& b) {
    for (const std::string& entry : u) {
      if (entry.find(a) != std::string::npos && entry.find(b) != std::string::npos &&
          entry.find("robot.urdf") != std::string::npos) {
        return true;
      }
    }
    return false;
  };
  EXPECT_TRUE(listed("camera_link", "<distortion>")) << ::testing::PrintToString(u);
  EXPECT_TRUE(listed("mast_link", "360 deg")) << ::testing::PrintToString(u);
  EXPECT_TRUE(listed("imu_link", "IMU block")) << ::testing::PrintToString(u);
  // Written and read back: mapped once, the sensors' keys kept.
  const std::string yaml = scenario::ScenarioToYaml(s);
  EXPECT_EQ(scenario::ScenarioToYaml(scenario::ParseScenario(yaml, "resolved")), yaml);
}

TEST_F(UrdfRobotTest, TrackedRobotFromSprocketsAndRoadWheels) {
  std::string u =
      "<?xml version='1.0'?>\n<robot name='tracked'>\n<link name='base_link'>"
      "<inertial><origin xyz='0 0 0.1'/><mass value='30'/><inertia ixx='1' ixy='0' ixz='0' iyy='1' "
      "iyz='0' "
      "izz='1'/></inertial><collision><origin xyz='0 0 0.1'/><geometry>"
      "<box size='0.7 0.4 0.2'/></geometry></collision></link>\n";
  for (int side = 0; side < 2; ++side) {
    const double y = side == 0 ? 0.25 : -0.25;
    const std::string s = side == 0 ? "left" : "right";
    u += WheelLink(s + "_sprocket", 0.09, 0.1, 0.0);
    u += TurningJoint(s + "_sprocket_joint", s + "_sprocket", 0.3, y, 0.05);
    for (int k = 0; k < 5; ++k) {
      const std::string n = s + "_road_wheel_" + std::to_string(k);
      u += WheelLink(n, 0.05, 0.1, 0.0);
      u += TurningJoint(n + "_joint", n, -0.24 + 0.12 * k, y, 0.0);
    }
  }
  u += "</robot>\n";
  const scenario::Scenario s = Load(u);
  const robot::TrackedVehicleOptions& v = s.robot.vehicle;
  EXPECT_EQ(v.contact, robot::TrackedVehicleOptions::Contact::kTracks);
  EXPECT_NEAR(v.sprocket_radius_m, 0.09, 5e-10);
  ASSERT_EQ(v.station_x_m.size(), 5u);
  EXPECT_NEAR(v.station_x_m[0], -0.24, 5e-10);
  EXPECT_NEAR(v.track_contact_length_m, 0.48 + 0.1, 5e-10);
  EXPECT_NEAR(v.com_height_m, 0.15, 5e-10);        // base_link 0.05 m above the ground
  EXPECT_NEAR(v.ground_clearance_m, 0.05, 5e-10);  // the box's underside at base_link
}

// Clearpath Jackal from its URDF (scenes/calibration/jackal.urdf): the vehicle's keys
// exactly the shipped icr_turns_jackal.yaml's, so that the two runs are the same run.
TEST_F(UrdfRobotTest, JackalFromItsUrdfIsTheShippedScenesVehicle) {
  const std::string scenes = std::string(TRACKBED_SOURCE_DIR) + "/scenes/calibration/";
  const scenario::Scenario shipped = scenario::LoadScenario(scenes + "icr_turns_jackal.yaml");
  const scenario::Scenario urdf = scenario::LoadScenario(scenes + "icr_turns_jackal_urdf.yaml");
  EXPECT_EQ(archive::ToYaml(archive::Write(urdf.robot.vehicle)),
            archive::ToYaml(archive::Write(shipped.robot.vehicle)));
  EXPECT_EQ(archive::ToYaml(archive::Write(urdf.robot.stereo)),
            archive::ToYaml(archive::Write(shipped.robot.stereo)));
  ASSERT_EQ(urdf.robot.description->unmapped.size(), 1u);  // the inertia tensors
}

TEST_F(UrdfRobotTest, ErrorsNameTheFileAndTheElement) {
  // urdfdom's own error (a joint's child that is no link), captured, not printed.
  std::string e = ErrorOf(
      "<robot name='r'><link name='a'/><joint name='j' type='fixed'><parent link='a'/>"
      "<child link='missing'/></joint></robot>");
  EXPECT_NE(e.find("robot.description.file"), std::string::npos) << e;
  EXPECT_NE(e.find("robot.urdf"), std::string::npos) << e;
  EXPECT_NE(e.find("missing"), std::string::npos) << e;
  // Wheels on one side only.
  std::string one_side = SkidSteer();
  for (const char* n : {"front_right_wheel_joint", "rear_right_wheel_joint"}) {
    const std::size_t at = one_side.find(std::string("name='") + n);
    one_side.replace(one_side.find("continuous", at), 10, "fixed");
  }
  e = ErrorOf(one_side);
  EXPECT_NE(e.find("left-right pairs"), std::string::npos) << e;
  EXPECT_NE(e.find("robot 'skid4'"), std::string::npos) << e;
  // A xacro file.
  e = ErrorOf("<robot xmlns:xacro='http://www.ros.org/wiki/xacro' name='r'/>", "r.urdf.xacro");
  EXPECT_NE(e.find("xacro robot.urdf.xacro > robot.urdf"), std::string::npos) << e;
  EXPECT_NE(e.find("r.urdf.xacro"), std::string::npos) << e;
}

}  // namespace
}  // namespace trackbed
