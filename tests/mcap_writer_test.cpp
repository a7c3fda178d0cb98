// The MCAP writer and the ROS 2 messages (recording/), read back by independent
// readers: the reference TypeScript MCAP reader (@mcap/core, streaming with CRC checks
// and seeking through the summary), the CRCs recomputed, and every message decoded by
// Foxglove's ROS 2 parser and CDR decoder (tests/mcap/check_mcap.mjs; the npm packages
// are installed into the build folder by the test fixture `mcap_readers`).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "trackbed/recording/mcap_writer.h"
#include "trackbed/recording/ros2_messages.h"

#include "mcap_readers.h"

namespace trackbed::recording {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

template <typename M>
std::uint16_t Channel(McapWriter* w, const M& m, const std::string& topic,
                      const std::map<std::string, std::string>& metadata = {}) {
  const MessageSchema& s = SchemaOf(m);
  return w->AddChannel(w->AddSchema(s.name, "ros2msg", s.definition), topic, "cdr", metadata);
}

Header At(double t, const std::string& frame) { return {Time::FromSeconds(t), frame}; }

// A bag of every message type: 200 steps of 10 ms, small chunks so that there are many.
void WriteBag(const std::string& path) {
  McapOptions options;
  options.chunk_size_bytes = 4096;
  McapWriter w(path, options);
  const std::uint16_t clock = Channel(&w, Clock{}, "/clock");
  const std::uint16_t tf = Channel(&w, TFMessage{}, "/tf");
  const std::uint16_t odom = Channel(&w, Odometry{}, "/fused/odom");
  const std::uint16_t imu = Channel(&w, Imu{}, "/imu");
  const std::uint16_t joints = Channel(&w, JointState{}, "/joint_states");
  const std::uint16_t scan = Channel(&w, LaserScan{}, "/scan");
  const std::uint16_t image = Channel(&w, CompressedImage{}, "/stereo/left/image_raw/compressed");
  const std::uint16_t info = Channel(&w, CameraInfo{}, "/stereo/left/camera_info",
                                     {{"offered_qos_profiles", "- durability: 1\n"}});
  for (int i = 0; i < 200; ++i) {
    const double t = 0.01 * i;
    const std::uint64_t ns = Time::FromSeconds(t).Nanoseconds();
    const auto write = [&](std::uint16_t c, const std::vector<std::uint8_t>& d) {
      w.Write(c, ns, ns, d);
    };
    write(clock, Serialize(Clock{Time::FromSeconds(t)}));
    TransformStamped odom_tf{
        At(t, "odom"), "base_link", {{0.5 * t, -0.25 * t, 0.01}, {0, 0, 0.6, 0.8}}};
    write(tf, Serialize(TFMessage{{odom_tf}}));
    Odometry o;
    o.header = At(t, "odom");
    o.child_frame_id = "base_link";
    o.pose = odom_tf.transform;
    o.pose_covariance[0] = 0.01 * (i + 1);
    o.linear = {0.5, 0, 0};
    o.angular = {0, 0, 0.25};
    write(odom, Serialize(o));
    Imu m;
    m.header = At(t, "imu_link");
    m.orientation_covariance[0] = -1.0;
    m.angular_velocity = {0.001 * i, -0.002, 0.25};
    m.linear_acceleration = {0.1, 0.0, 9.81};
    write(imu, Serialize(m));
    write(joints, Serialize(JointState{At(t, ""),
                                       {"left_sprocket", "right_sprocket"},
                                       {0.1 * i, 0.12 * i},
                                       {10.0, 12.0},
                                       {}}));
    if (i % 10 == 0) {
      LaserScan s{At(t, "range_sensor"),
                  -1.0f,
                  1.0f,
                  0.5f,
                  0.0f,
                  0.1f,
                  0.1f,
                  10.0f,
                  {1.0f, 2.0f, 3.5f, 10.0f, 0.25f},
                  {}};
      write(scan, Serialize(s));
      std::vector<std::uint8_t> png(37 + i);
      for (std::size_t k = 0; k < png.size(); ++k) png[k] = static_cast<std::uint8_t>(k * 7 + i);
      write(image, Serialize(CompressedImage{At(t, "left_camera_optical"), "png", png}));
      CameraInfo ci{At(t, "left_camera_optical"),
                    480,
                    640,
                    "plumb_bob",
                    {0, 0, 0, 0, 0},
                    {381.4, 0, 319.5, 0, 381.4, 239.5, 0, 0, 1},
                    {1, 0, 0, 0, 1, 0, 0, 0, 1},
                    {381.4, 0, 319.5, 0, 0, 381.4, 239.5, 0, 0, 0, 1, 0}};
      write(info, Serialize(ci));
    }
  }
  w.Close();
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(McapWriterTest, IndependentReadersReadEveryRecordAndMessage) {
  const std::string path = (fs::temp_directory_path() / "mcap_writer_test.mcap").string();
  WriteBag(path);
  const json r = testing_mcap::ReadWithIndependentReaders(path);
  ASSERT_TRUE(r.is_object());
  EXPECT_TRUE(r["problems"].empty()) << r["problems"].dump();
  EXPECT_EQ(r["header"]["profile"], "ros2");
  const json& st = r["statistics"];
  EXPECT_EQ(st["messageCount"], 200 * 5 + 20 * 3);
  EXPECT_EQ(st["schemaCount"], 8);
  EXPECT_EQ(st["channelCount"], 8);
  EXPECT_GT(st["chunkCount"].get<int>(), 5);
  EXPECT_EQ(r["chunkIndexes"], st["chunkCount"]);
  EXPECT_EQ(st["startNs"], "0");
  EXPECT_EQ(st["endNs"], "1990000000");
  EXPECT_EQ(r["streamed"]["Message"], st["messageCount"]);  // out of the chunks
  EXPECT_EQ(r["streamed"]["DataEnd"], 1);
  EXPECT_EQ(r["streamed"]["Footer"], 1);
  const json& c = r["channels"];
  EXPECT_EQ(c["/clock"]["schema"], "rosgraph_msgs/msg/Clock");
  EXPECT_EQ(c["/clock"]["schemaEncoding"], "ros2msg");
  EXPECT_EQ(c["/clock"]["messageEncoding"], "cdr");
  EXPECT_EQ(c["/clock"]["count"], 200);
  EXPECT_TRUE(c["/clock"]["sequenceOk"]);
  EXPECT_EQ(c["/clock"]["last"]["clock"]["sec"], 1);
  EXPECT_EQ(c["/clock"]["last"]["clock"]["nanosec"], 990000000);
  const json& tf = c["/tf"]["last"]["transforms"][0];
  EXPECT_EQ(tf["header"]["frame_id"], "odom");
  EXPECT_EQ(tf["child_frame_id"], "base_link");
  EXPECT_DOUBLE_EQ(tf["transform"]["translation"]["x"], 0.5 * 1.99);
  EXPECT_DOUBLE_EQ(tf["transform"]["rotation"]["w"], 0.8);
  const json& o = c["/fused/odom"]["last"];
  EXPECT_EQ(c["/fused/odom"]["schema"], "nav_msgs/msg/Odometry");
  EXPECT_DOUBLE_EQ(o["pose"]["pose"]["position"]["y"], -0.25 * 1.99);
  EXPECT_DOUBLE_EQ(o["pose"]["covariance"][0], 2.0);
  EXPECT_DOUBLE_EQ(o["twist"]["twist"]["angular"]["z"], 0.25);
  const json& imu = c["/imu"]["last"];
  EXPECT_DOUBLE_EQ(imu["orientation_covariance"][0], -1.0);
  EXPECT_DOUBLE_EQ(imu["angular_velocity"]["x"], 0.199);
  EXPECT_DOUBLE_EQ(imu["linear_acceleration"]["z"], 9.81);
  const json& js = c["/joint_states"]["last"];
  EXPECT_EQ(js["name"][1], "right_sprocket");
  EXPECT_DOUBLE_EQ(js["position"][0], 0.1 * 199);
  EXPECT_TRUE(js["effort"].empty());
  const json& scan = c["/scan"]["last"];
  EXPECT_EQ(c["/scan"]["count"], 20);
  EXPECT_FLOAT_EQ(scan["ranges"][2].get<float>(), 3.5f);
  EXPECT_FLOAT_EQ(scan["range_max"].get<float>(), 10.0f);
  const json& img = c["/stereo/left/image_raw/compressed"]["last"];
  EXPECT_EQ(img["format"], "png");
  ASSERT_EQ(img["data"].size(), 37u + 190u);
  EXPECT_EQ(img["data"][5], (5 * 7 + 190) % 256);
  const json& ci = c["/stereo/left/camera_info"];
  EXPECT_EQ(ci["metadata"]["offered_qos_profiles"], "- durability: 1\n");
  EXPECT_EQ(ci["last"]["width"], 640);
  EXPECT_EQ(ci["last"]["distortion_model"], "plumb_bob");
  EXPECT_DOUBLE_EQ(ci["last"]["p"][6], 239.5);
  EXPECT_EQ(ci["last"]["roi"]["do_rectify"], false);
}

TEST(McapWriterTest, TheSameCallsGiveTheSameBytes) {
  const fs::path dir = fs::temp_directory_path();
  WriteBag((dir / "mcap_a.mcap").string());
  WriteBag((dir / "mcap_b.mcap").string());
  const std::string a = Slurp((dir / "mcap_a.mcap").string());
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, Slurp((dir / "mcap_b.mcap").string()));
}

TEST(McapWriterTest, RefusesWhatTheFormatCannotHold) {
  const std::string path = (fs::temp_directory_path() / "mcap_bad.mcap").string();
  McapWriter w(path);
  EXPECT_THROW(w.AddChannel(3, "/x", "cdr"), std::invalid_argument);
  EXPECT_THROW(w.Write(0, 0, 0, {}), std::invalid_argument);
  EXPECT_THROW(Time::FromSeconds(-1.0), std::invalid_argument);
  w.Close();
  EXPECT_THROW(w.Write(0, 0, 0, {}), std::logic_error);
  EXPECT_THROW(McapWriter("/nonexistent_dir/x.mcap"), std::runtime_error);
}

}  // namespace
}  // namespace trackbed::recording
