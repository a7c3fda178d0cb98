// A run as a ROS 2 bag (runner/run_bag.h, docs/mcap.md), read by independent readers
// (tests/mcap_readers.h): the corridor and the park, with the images, each write
// run.mcap and metadata.yaml (the corridor with its range sensor on); every record and CRC is
// valid; topics, types and frames are the documented ones; each topic has one message per row of
// the file it mirrors, and its last message equals that row; `trackbed export-mcap` on the folder
// writes the same bytes, and refuses a folder that is not a run's.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "mcap_readers.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using trackbed::testing_cli::Slurp;

// The data rows of a CSV or TUM file (header and comments skipped), as numbers.
std::vector<std::vector<double>> Rows(const fs::path& file, char separator) {
  std::istringstream in(Slurp(file));
  std::vector<std::vector<double>> rows;
  std::string line;
  if (separator == ',') std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::replace(line.begin(), line.end(), separator, ' ');
    std::istringstream fields(line);
    std::vector<double> row;
    for (double v; fields >> v;) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

double Seconds(const json& stamp) {
  return stamp["sec"].get<double>() + stamp["nanosec"].get<double>() * 1e-9;
}

// A decoded pose (geometry_msgs Pose or Transform) against a TUM row.
void ExpectPose(const json& position, const json& orientation, const std::vector<double>& tum) {
  EXPECT_NEAR(position["x"].get<double>(), tum[1], 1e-12);
  EXPECT_NEAR(position["y"].get<double>(), tum[2], 1e-12);
  EXPECT_NEAR(position["z"].get<double>(), tum[3], 1e-12);
  // q and -q are one rotation.
  const double sign = orientation["w"].get<double>() * tum[7] < 0 ? -1.0 : 1.0;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(sign * orientation[std::string(1, "xyzw"[i])].get<double>(), tum[4 + i], 1e-8);
  }
}

// scan.csv's rows, `inf` included (which the stream parse above refuses).
std::vector<std::vector<double>> ScanRows(const fs::path& file) {
  std::istringstream in(Slurp(file));
  std::vector<std::vector<double>> rows;
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');)
      row.push_back(std::strtod(f.c_str(), nullptr));
    rows.push_back(row);
  }
  return rows;
}

// /scan against scan.csv: one message per row, the last one's ranges the row's as
// float32, the fan and limits the scenario's.
void CheckScan(const json& c, const fs::path& run) {
  const auto scans = ScanRows(run / "scan.csv");
  ASSERT_GT(scans.size(), 10u);
  const json& scan = c["/scan"];
  EXPECT_EQ(scan["schema"], "sensor_msgs/msg/LaserScan");
  EXPECT_EQ(scan["count"], scans.size());
  const json& m = scan["last"];
  EXPECT_EQ(m["header"]["frame_id"], "range_sensor");
  EXPECT_NEAR(Seconds(m["header"]["stamp"]), scans.back()[0], 1e-9);
  ASSERT_EQ(m["ranges"].size(), 360u);
  EXPECT_FLOAT_EQ(m["angle_increment"].get<float>(), static_cast<float>(2 * M_PI / 360));
  EXPECT_FLOAT_EQ(m["range_max"].get<float>(), 8.0f);
  int returns = 0;
  for (std::size_t k = 0; k < 360; ++k) {
    const double csv = scans.back()[k + 1];
    if (std::isinf(csv)) {
      EXPECT_TRUE(m["ranges"][k].is_null()) << k;  // JSON.stringify writes Infinity as null
      continue;
    }
    ++returns;
    EXPECT_EQ(m["ranges"][k].get<float>(), static_cast<float>(csv)) << k;
  }
  EXPECT_GT(returns, 90);  // the corridor's walls on both sides
}

void CheckRunBag(const std::string& scene, const std::string& tag, const std::string& sets) {
  const fs::path out = trackbed::testing_cli::FreshTempDir("trackbed_run_bag_test_", tag);
  const auto r = trackbed::testing_cli::RunTrackbed(
      "run " + scene + " --set duration_s=6 --set outputs.mcap_images=true" + sets + " --out " +
          (out / "run").string(),
      out / "io");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const fs::path run = out / "run";
  const json bag = trackbed::testing_mcap::ReadWithIndependentReaders((run / "run.mcap").string());
  ASSERT_TRUE(bag.is_object());
  EXPECT_TRUE(bag["problems"].empty()) << bag["problems"].dump();
  EXPECT_EQ(bag["header"]["profile"], "ros2");
  const json& c = bag["channels"];
  const std::vector<std::pair<std::string, std::string>> topics = {
      {"/clock", "rosgraph_msgs/msg/Clock"},
      {"/tf", "tf2_msgs/msg/TFMessage"},
      {"/tf_static", "tf2_msgs/msg/TFMessage"},
      {"/ground_truth/odom", "nav_msgs/msg/Odometry"},
      {"/wheel_odometry/odom", "nav_msgs/msg/Odometry"},
      {"/visual_odometry/odom", "nav_msgs/msg/Odometry"},
      {"/fused/odom", "nav_msgs/msg/Odometry"},
      {"/ekf/odom", "nav_msgs/msg/Odometry"},
      {"/imu", "sensor_msgs/msg/Imu"},
      {"/joint_states", "sensor_msgs/msg/JointState"},
      {"/stereo/left/camera_info", "sensor_msgs/msg/CameraInfo"},
      {"/stereo/right/camera_info", "sensor_msgs/msg/CameraInfo"},
      {"/stereo/left/image_raw/compressed", "sensor_msgs/msg/CompressedImage"},
      {"/stereo/right/image_raw/compressed", "sensor_msgs/msg/CompressedImage"}};
  for (const auto& [topic, type] : topics) {
    ASSERT_TRUE(c.contains(topic)) << topic;
    EXPECT_EQ(c[topic]["schema"], type) << topic;
    EXPECT_EQ(c[topic]["messageEncoding"], "cdr");
    EXPECT_EQ(c[topic]["schemaEncoding"], "ros2msg");
    EXPECT_TRUE(c[topic]["sequenceOk"]) << topic;
  }
  EXPECT_NE(
      c["/tf_static"]["metadata"]["offered_qos_profiles"].get<std::string>().find("durability: 1"),
      std::string::npos);
  // One message per row, the last equal to the last row.
  const auto gt = Rows(run / "ground_truth.tum", ' ');
  EXPECT_EQ(c["/clock"]["count"], gt.size());
  EXPECT_NEAR(Seconds(c["/clock"]["last"]["clock"]), gt.back()[0], 1e-9);
  EXPECT_EQ(c["/ground_truth/odom"]["count"], gt.size());
  const json& gt_msg = c["/ground_truth/odom"]["last"];
  EXPECT_EQ(gt_msg["header"]["frame_id"], "map");
  EXPECT_EQ(gt_msg["child_frame_id"], "base_link_ground_truth");
  ExpectPose(gt_msg["pose"]["pose"]["position"], gt_msg["pose"]["pose"]["orientation"], gt.back());
  const auto twist = Rows(run / "ground_truth_twist.csv", ',');
  EXPECT_DOUBLE_EQ(gt_msg["twist"]["twist"]["linear"]["x"], twist.back()[1]);
  EXPECT_DOUBLE_EQ(gt_msg["twist"]["twist"]["angular"]["z"], twist.back()[6]);
  for (const char* name : {"wheel_odometry", "visual_odometry", "fused", "ekf"}) {
    const auto est = Rows(run / (std::string(name) + ".tum"), ' ');
    const json& ch = c["/" + std::string(name) + "/odom"];
    EXPECT_EQ(ch["count"], est.size()) << name;
    EXPECT_EQ(ch["last"]["header"]["frame_id"], "odom");
    ExpectPose(ch["last"]["pose"]["pose"]["position"], ch["last"]["pose"]["pose"]["orientation"],
               est.back());
  }
  EXPECT_EQ(c["/fused/odom"]["last"]["child_frame_id"], "base_link");
  const auto fused = Rows(run / "fused.tum", ' ');
  const json& tf = c["/tf"]["last"]["transforms"];
  EXPECT_EQ(c["/tf"]["count"], fused.size());
  EXPECT_EQ(tf[0]["header"]["frame_id"], "map");
  EXPECT_EQ(tf[0]["child_frame_id"], "odom");
  EXPECT_EQ(tf[1]["child_frame_id"], "base_link");
  ExpectPose(tf[1]["transform"]["translation"], tf[1]["transform"]["rotation"], fused.back());
  const auto imu = Rows(run / "imu.csv", ',');
  EXPECT_EQ(c["/imu"]["count"], imu.size());
  EXPECT_DOUBLE_EQ(c["/imu"]["last"]["angular_velocity"]["z"], imu.back()[3]);
  EXPECT_DOUBLE_EQ(c["/imu"]["last"]["linear_acceleration"]["z"], imu.back()[6]);
  EXPECT_EQ(c["/imu"]["last"]["header"]["frame_id"], "imu_link");
  const auto enc = Rows(run / "encoders.csv", ',');
  EXPECT_EQ(c["/joint_states"]["count"], enc.size());
  EXPECT_NEAR(c["/joint_states"]["last"]["position"][1].get<double>(),
              enc.back()[2] * 2 * M_PI / 4096, 1e-12);
  const json calib = json::parse(Slurp(run / "stereo_calibration.json"));
  const json& info = c["/stereo/left/camera_info"]["last"];
  EXPECT_EQ(info["width"], calib["width_px"]);
  EXPECT_DOUBLE_EQ(info["k"][0], calib["fx"]);
  EXPECT_DOUBLE_EQ(info["k"][5], calib["cy"]);
  // The images as the stack received them: one per frame, the PNG's bytes, stamped as
  // their camera_info.
  const auto frames = Rows(run / "camera/times.txt", ' ');
  ASSERT_GT(frames.size(), 50u);
  for (const char* side : {"left", "right"}) {
    const std::string topic = std::string("/stereo/") + side;
    const json& image = c[topic + "/image_raw/compressed"];
    EXPECT_EQ(image["count"], frames.size());
    EXPECT_EQ(c[topic + "/camera_info"]["count"], frames.size());
    EXPECT_EQ(image["last"]["format"], "png");
    EXPECT_EQ(image["last"]["header"]["frame_id"], std::string(side) + "_camera_optical");
    EXPECT_NEAR(Seconds(image["last"]["header"]["stamp"]), frames.back()[0], 1e-9);
    EXPECT_EQ(image["last"]["header"]["stamp"],
              c[topic + "/camera_info"]["last"]["header"]["stamp"]);
    char name[16];
    std::snprintf(name, sizeof(name), "%06zu.png", frames.size() - 1);
    const std::string png = Slurp(run / "camera" / side / name);
    EXPECT_EQ(image["last"]["data"]["bytes"], png.size());
    EXPECT_EQ(image["last"]["data"]["crc32"],
              crc32(0, reinterpret_cast<const Bytef*>(png.data()), static_cast<uInt>(png.size())));
  }
  if (!sets.empty()) {
    CheckScan(c, run);
  } else {
    EXPECT_FALSE(c.contains("/scan"));
  }
  const json& statics = c["/tf_static"]["last"]["transforms"];
  EXPECT_EQ(statics[0]["child_frame_id"], "left_camera_optical");
  EXPECT_DOUBLE_EQ(statics[0]["transform"]["translation"]["x"], calib["T_body_left"][0][3]);
  // rosbag2's metadata.yaml: the bag's file, its topics and counts.
  const std::string meta = Slurp(run / "metadata.yaml");
  EXPECT_EQ(
      meta.rfind("rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n", 0),
      0u);
  EXPECT_NE(meta.find("relative_file_paths:\n    - run.mcap"), std::string::npos);
  EXPECT_NE(meta.find("name: /fused/odom\n        type: nav_msgs/msg/Odometry"), std::string::npos);
  EXPECT_NE(
      meta.find("message_count: " + std::to_string(bag["statistics"]["messageCount"].get<int>())),
      std::string::npos);
  // Converted later, the same bytes.
  const std::string bytes = Slurp(run / "run.mcap");
  fs::remove(run / "run.mcap");
  const auto e = trackbed::testing_cli::RunTrackbed("export-mcap " + run.string(), out / "io2");
  ASSERT_EQ(e.exit_code, 0) << e.stderr_text;
  EXPECT_EQ(Slurp(run / "run.mcap"), bytes);
}

TEST(RunBagTest, TheCorridorsBagHoldsEveryTopicAsItsFilesHaveIt) {
  CheckRunBag("scenes/corridor.yaml", "corridor", " --set robot.range_sensor.enabled=true");
}

TEST(RunBagTest, TheParksBagHoldsEveryTopicAsItsFilesHaveIt) {
  CheckRunBag("scenes/outdoor.yaml", "outdoor", "");
}

TEST(RunBagTest, ExportRefusesAFolderThatIsNotARunsAndAMalformedFile) {
  const fs::path out = trackbed::testing_cli::FreshTempDir("trackbed_run_bag_test_", "bad");
  auto r = trackbed::testing_cli::RunTrackbed("export-mcap " + out.string(), out / "io");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("not a run folder"), std::string::npos) << r.stderr_text;
  // A run whose IMU log is cut mid-row: the error names the file and the line.
  r = trackbed::testing_cli::RunTrackbed(
      "run scenes/corridor.yaml --set duration_s=1 --set outputs.mcap=false --out " +
          (out / "run").string(),
      out / "io");
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  EXPECT_FALSE(fs::exists(out / "run" / "run.mcap"));
  {
    std::ofstream imu(out / "run" / "imu.csv", std::ios::app);
    imu << "0.5,1,2\n";
  }
  r = trackbed::testing_cli::RunTrackbed("export-mcap " + (out / "run").string(), out / "io");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.stderr_text.find("imu.csv:"), std::string::npos) << r.stderr_text;
  EXPECT_NE(r.stderr_text.find("3 fields, the header has 7"), std::string::npos) << r.stderr_text;
}

}  // namespace
