// ROS 2 messages in CDR and their schema texts (see ros2_messages.h). The definitions
// are the fields of the ROS 2 .msg files (rcl_interfaces, common_interfaces and
// geometry2, Humble), comments left out; a field of a type from the same package names
// it without the package, as the .msg files do.
#include "trackbed/recording/ros2_messages.h"

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "trackbed/recording/cdr_writer.h"

namespace trackbed::recording {
namespace {

struct MsgFile {
  const char* text;
  std::vector<const char*> uses;  // full names of the types its fields use
};

const std::map<std::string, MsgFile>& MsgFiles() {
  static const std::map<std::string, MsgFile> files = {
      {"builtin_interfaces/Time", {"int32 sec\nuint32 nanosec\n", {}}},
      {"std_msgs/Header",
       {"builtin_interfaces/Time stamp\nstring frame_id\n", {"builtin_interfaces/Time"}}},
      {"rosgraph_msgs/Clock", {"builtin_interfaces/Time clock\n", {"builtin_interfaces/Time"}}},
      {"geometry_msgs/Vector3", {"float64 x\nfloat64 y\nfloat64 z\n", {}}},
      {"geometry_msgs/Point", {"float64 x\nfloat64 y\nfloat64 z\n", {}}},
      {"geometry_msgs/Quaternion", {"float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n", {}}},
      {"geometry_msgs/Pose",
       {"Point position\nQuaternion orientation\n",
        {"geometry_msgs/Point", "geometry_msgs/Quaternion"}}},
      {"geometry_msgs/PoseWithCovariance",
       {"Pose pose\nfloat64[36] covariance\n", {"geometry_msgs/Pose"}}},
      {"geometry_msgs/Twist", {"Vector3 linear\nVector3 angular\n", {"geometry_msgs/Vector3"}}},
      {"geometry_msgs/TwistWithCovariance",
       {"Twist twist\nfloat64[36] covariance\n", {"geometry_msgs/Twist"}}},
      {"geometry_msgs/Transform",
       {"Vector3 translation\nQuaternion rotation\n",
        {"geometry_msgs/Vector3", "geometry_msgs/Quaternion"}}},
      {"geometry_msgs/TransformStamped",
       {"std_msgs/Header header\nstring child_frame_id\nTransform transform\n",
        {"std_msgs/Header", "geometry_msgs/Transform"}}},
      {"tf2_msgs/TFMessage",
       {"geometry_msgs/TransformStamped[] transforms\n", {"geometry_msgs/TransformStamped"}}},
      {"nav_msgs/Odometry",
       {"std_msgs/Header header\nstring child_frame_id\n"
        "geometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist\n",
        {"std_msgs/Header", "geometry_msgs/PoseWithCovariance",
         "geometry_msgs/TwistWithCovariance"}}},
      {"sensor_msgs/Imu",
       {"std_msgs/Header header\ngeometry_msgs/Quaternion orientation\n"
        "float64[9] orientation_covariance\ngeometry_msgs/Vector3 angular_velocity\n"
        "float64[9] angular_velocity_covariance\ngeometry_msgs/Vector3 linear_acceleration\n"
        "float64[9] linear_acceleration_covariance\n",
        {"std_msgs/Header", "geometry_msgs/Quaternion", "geometry_msgs/Vector3"}}},
      {"sensor_msgs/JointState",
       {"std_msgs/Header header\nstring[] name\nfloat64[] position\nfloat64[] velocity\n"
        "float64[] effort\n",
        {"std_msgs/Header"}}},
      {"sensor_msgs/LaserScan",
       {"std_msgs/Header header\nfloat32 angle_min\nfloat32 angle_max\n"
        "float32 angle_increment\nfloat32 time_increment\nfloat32 scan_time\n"
        "float32 range_min\nfloat32 range_max\nfloat32[] ranges\nfloat32[] intensities\n",
        {"std_msgs/Header"}}},
      {"sensor_msgs/CompressedImage",
       {"std_msgs/Header header\nstring format\nuint8[] data\n", {"std_msgs/Header"}}},
      {"sensor_msgs/RegionOfInterest",
       {"uint32 x_offset\nuint32 y_offset\nuint32 height\nuint32 width\nbool do_rectify\n", {}}},
      {"sensor_msgs/CameraInfo",
       {"std_msgs/Header header\nuint32 height\nuint32 width\nstring distortion_model\n"
        "float64[] d\nfloat64[9] k\nfloat64[9] r\nfloat64[12] p\nuint32 binning_x\n"
        "uint32 binning_y\nRegionOfInterest roi\n",
        {"std_msgs/Header", "sensor_msgs/RegionOfInterest"}}},
  };
  return files;
}

void Put(CdrWriter& w, const Time& t) { w.Int32(t.sec).UInt32(t.nanosec); }
void Put(CdrWriter& w, const Header& h) {
  Put(w, h.stamp);
  w.String(h.frame_id);
}
void Put(CdrWriter& w, const Pose& p) {
  w.Array(p.position.data(), 3).Array(p.orientation_xyzw.data(), 4);
}

}  // namespace

Time Time::FromSeconds(double t_s) {
  if (!(t_s >= 0.0) || t_s > 2147483647.0) {
    throw std::invalid_argument("ROS time: seconds out of range: " + std::to_string(t_s));
  }
  const auto ns = static_cast<std::uint64_t>(std::llround(t_s * 1e9));
  return {static_cast<std::int32_t>(ns / 1000000000ULL),
          static_cast<std::uint32_t>(ns % 1000000000ULL)};
}

std::uint64_t Time::Nanoseconds() const {
  return static_cast<std::uint64_t>(sec) * 1000000000ULL + nanosec;
}

MessageSchema ComposeSchema(const std::string& type) {
  const auto& files = MsgFiles();
  std::string text = files.at(type).text;
  std::set<std::string> seen{type};
  std::vector<std::string> stack(files.at(type).uses.rbegin(), files.at(type).uses.rend());
  while (!stack.empty()) {
    const std::string dep = stack.back();
    stack.pop_back();
    if (!seen.insert(dep).second) continue;
    const MsgFile& f = files.at(dep);
    text += std::string(80, '=') + "\nMSG: " + dep + "\n" + f.text;
    for (auto it = f.uses.rbegin(); it != f.uses.rend(); ++it) stack.push_back(*it);
  }
  const std::size_t slash = type.find('/');
  return {type.substr(0, slash) + "/msg" + type.substr(slash), text};
}

std::vector<std::uint8_t> Serialize(const Clock& m) {
  CdrWriter w;
  Put(w, m.clock);
  return w.Take();
}

std::vector<std::uint8_t> Serialize(const TFMessage& m) {
  CdrWriter w;
  w.UInt32(static_cast<std::uint32_t>(m.transforms.size()));
  for (const TransformStamped& t : m.transforms) {
    Put(w, t.header);
    w.String(t.child_frame_id);
    Put(w, t.transform);
  }
  return w.Take();
}

std::vector<std::uint8_t> Serialize(const Odometry& m) {
  CdrWriter w;
  Put(w, m.header);
  w.String(m.child_frame_id);
  Put(w, m.pose);
  w.Array(m.pose_covariance.data(), 36);
  w.Array(m.linear.data(), 3).Array(m.angular.data(), 3).Array(m.twist_covariance.data(), 36);
  return w.Take();
}

std::vector<std::uint8_t> Serialize(const Imu& m) {
  CdrWriter w;
  Put(w, m.header);
  w.Array(m.orientation_xyzw.data(), 4).Array(m.orientation_covariance.data(), 9);
  w.Array(m.angular_velocity.data(), 3).Array(m.angular_velocity_covariance.data(), 9);
  w.Array(m.linear_acceleration.data(), 3).Array(m.linear_acceleration_covariance.data(), 9);
  return w.Take();
}

std::vector<std::uint8_t> Serialize(const JointState& m) {
  CdrWriter w;
  Put(w, m.header);
  w.Strings(m.name).Sequence(m.position).Sequence(m.velocity).Sequence(m.effort);
  return w.Take();
}

std::vector<std::uint8_t> Serialize(const LaserScan& m) {
  CdrWriter w;
  Put(w, m.header);
  w.Float32(m.angle_min).Float32(m.angle_max).Float32(m.angle_increment);
  w.Float32(m.time_increment).Float32(m.scan_time).Float32(m.range_min).Float32(m.range_max);
  w.Sequence(m.ranges).Sequence(m.intensities);
  return w.Take();
}

std::vector<std::uint8_t> Serialize(const CompressedImage& m) {
  CdrWriter w;
  Put(w, m.header);
  w.String(m.format).Bytes(m.data);
  return w.Take();
}

std::vector<std::uint8_t> Serialize(const CameraInfo& m) {
  CdrWriter w;
  Put(w, m.header);
  w.UInt32(m.height).UInt32(m.width).String(m.distortion_model).Sequence(m.d);
  w.Array(m.k.data(), 9).Array(m.r.data(), 9).Array(m.p.data(), 12);
  w.UInt32(0).UInt32(0);                                  // binning_x, binning_y
  w.UInt32(0).UInt32(0).UInt32(0).UInt32(0).Bool(false);  // roi: the full image
  return w.Take();
}

}  // namespace trackbed::recording
