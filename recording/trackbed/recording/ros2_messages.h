// The ROS 2 messages a run is recorded as (field for field the .msg definitions of ROS 2
// Humble and later: rosgraph_msgs, tf2_msgs, nav_msgs, sensor_msgs and what they use),
// their CDR serialisation, and each type's schema text as rosbag2 stores it in MCAP
// (`ros2msg`: the type's definition, then each type it uses after a line of 80 '=' and
// `MSG: package/Type`).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace trackbed::recording {

struct Time {  // builtin_interfaces/msg/Time
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  /// From seconds since the run's start (>= 0), rounded to the nanosecond.
  static Time FromSeconds(double t_s);
  std::uint64_t Nanoseconds() const;
};

struct Header {  // std_msgs/msg/Header
  Time stamp;
  std::string frame_id;
};

struct Pose {  // geometry_msgs/msg/Pose (and Transform's translation and rotation)
  std::array<double, 3> position{};
  std::array<double, 4> orientation_xyzw{0, 0, 0, 1};
};

struct Clock {  // rosgraph_msgs/msg/Clock
  Time clock;
};

struct TransformStamped {  // geometry_msgs/msg/TransformStamped
  Header header;
  std::string child_frame_id;
  Pose transform;
};

struct TFMessage {  // tf2_msgs/msg/TFMessage
  std::vector<TransformStamped> transforms;
};

struct Odometry {  // nav_msgs/msg/Odometry
  Header header;
  std::string child_frame_id;
  Pose pose;
  std::array<double, 36> pose_covariance{};
  std::array<double, 3> linear{}, angular{};  // twist in child_frame_id's axes
  std::array<double, 36> twist_covariance{};
};

struct Imu {  // sensor_msgs/msg/Imu
  Header header;
  std::array<double, 4> orientation_xyzw{0, 0, 0, 1};
  std::array<double, 9> orientation_covariance{};  // element 0 at -1: no orientation
  std::array<double, 3> angular_velocity{};
  std::array<double, 9> angular_velocity_covariance{};
  std::array<double, 3> linear_acceleration{};
  std::array<double, 9> linear_acceleration_covariance{};
};

struct JointState {  // sensor_msgs/msg/JointState
  Header header;
  std::vector<std::string> name;
  std::vector<double> position, velocity, effort;
};

struct LaserScan {  // sensor_msgs/msg/LaserScan
  Header header;
  float angle_min = 0, angle_max = 0, angle_increment = 0, time_increment = 0, scan_time = 0;
  float range_min = 0, range_max = 0;
  std::vector<float> ranges, intensities;
};

struct CompressedImage {  // sensor_msgs/msg/CompressedImage
  Header header;
  std::string format;
  std::vector<std::uint8_t> data;
};

struct CameraInfo {  // sensor_msgs/msg/CameraInfo (its RegionOfInterest all zero)
  Header header;
  std::uint32_t height = 0, width = 0;
  std::string distortion_model;
  std::vector<double> d;
  std::array<double, 9> k{}, r{};
  std::array<double, 12> p{};
};

/// A message type as a schema: its ROS 2 name (`nav_msgs/msg/Odometry`) and its
/// `ros2msg` definition text with every dependency.
struct MessageSchema {
  std::string name;
  std::string definition;
};

/// Each message's ROS 2 type as its .msg file is named: `package/Type`.
inline const char* TypeOf(const Clock&) { return "rosgraph_msgs/Clock"; }
inline const char* TypeOf(const TFMessage&) { return "tf2_msgs/TFMessage"; }
inline const char* TypeOf(const Odometry&) { return "nav_msgs/Odometry"; }
inline const char* TypeOf(const Imu&) { return "sensor_msgs/Imu"; }
inline const char* TypeOf(const JointState&) { return "sensor_msgs/JointState"; }
inline const char* TypeOf(const LaserScan&) { return "sensor_msgs/LaserScan"; }
inline const char* TypeOf(const CompressedImage&) { return "sensor_msgs/CompressedImage"; }
inline const char* TypeOf(const CameraInfo&) { return "sensor_msgs/CameraInfo"; }

/// The schema of `package/Type`: `package/msg/Type` and the definition with every type
/// it uses, depth first, each once.
MessageSchema ComposeSchema(const std::string& type);

/// The schema of message type M, composed once.
template <class M>
const MessageSchema& SchemaOf(const M& m) {
  static const MessageSchema schema = ComposeSchema(TypeOf(m));
  return schema;
}

std::vector<std::uint8_t> Serialize(const Clock& m);
std::vector<std::uint8_t> Serialize(const TFMessage& m);
std::vector<std::uint8_t> Serialize(const Odometry& m);
std::vector<std::uint8_t> Serialize(const Imu& m);
std::vector<std::uint8_t> Serialize(const JointState& m);
std::vector<std::uint8_t> Serialize(const LaserScan& m);
std::vector<std::uint8_t> Serialize(const CompressedImage& m);
std::vector<std::uint8_t> Serialize(const CameraInfo& m);

}  // namespace trackbed::recording
