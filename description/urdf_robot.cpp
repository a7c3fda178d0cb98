// URDF robots through urdfdom, mapped onto trackbed's vehicle (see urdf_robot.h and
// docs/gazebo_users.md).
#include "trackbed/description/urdf_robot.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>
#include <Eigen/Geometry>

#include "sensor_reading.h"

namespace trackbed::description {

namespace {

constexpr double kPairM = 1e-3;    // a left and a right wheel at the same x [m]
constexpr double kTurnRad = 1e-9;  // a camera's roll or yaw taken as none [rad]
constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;  // [deg/rad]

// A derived value rounded to 1e-9 of its unit (a nanometre, a microgram, a nanodegree):
// sums and quotients of a file's decimals then give the decimals a scenario would
// (0.14 − 0.075 is 0.06500000000000002 in binary; rounded, it reads as 0.065 does).
double Rounded(double v) { return std::round(v * 1e9) / 1e9; }
Eigen::Vector3d Rounded(const Eigen::Vector3d& v) {
  return {Rounded(v.x()), Rounded(v.y()), Rounded(v.z())};
}

// urdfdom reports through console_bridge and returns null: its messages are collected
// while it parses, so that the error names what it names.
class CapturedMessages : public console_bridge::OutputHandler {
 public:
  CapturedMessages() { console_bridge::useOutputHandler(this); }
  ~CapturedMessages() override { console_bridge::restorePreviousOutputHandler(); }
  CapturedMessages(const CapturedMessages&) = delete;
  CapturedMessages& operator=(const CapturedMessages&) = delete;

  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) {
      text_ += (text_.empty() ? "" : "; ") + text;
    }
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

Eigen::Isometry3d ToEigen(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

bool Contains(const std::string& name, const char* part) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find(part) != std::string::npos;
}

// A wheel: a turning joint's child link with a cylinder, where it is in the root's frame.
struct Wheel {
  std::string link;
  Eigen::Vector3d center;
  double radius = 0.0, width = 0.0;
  bool sprocket = false;
};

// The first cylinder (collision, else visual) of a link.
const urdf::Cylinder* CylinderOf(const urdf::Link& link) {
  for (const urdf::CollisionSharedPtr& c : link.collision_array) {
    if (c && c->geometry && c->geometry->type == urdf::Geometry::CYLINDER) {
      return static_cast<const urdf::Cylinder*>(c->geometry.get());
    }
  }
  for (const urdf::VisualSharedPtr& v : link.visual_array) {
    if (v && v->geometry && v->geometry->type == urdf::Geometry::CYLINDER) {
      return static_cast<const urdf::Cylinder*>(v->geometry.get());
    }
  }
  return nullptr;
}

// The robot's links, each with its pose in the root's frame (joints at zero).
class RobotTree {
 public:
  explicit RobotTree(const urdf::ModelInterface& model) {
    Visit(*model.getRoot(), Eigen::Isometry3d::Identity(), true);
  }
  struct Placed {
    const urdf::Link* link;
    Eigen::Isometry3d pose;
    bool on_chassis;  ///< Fixed to the root link through fixed joints only.
  };
  const std::vector<Placed>& links() const { return links_; }

 private:
  void Visit(const urdf::Link& link, const Eigen::Isometry3d& pose, bool on_chassis) {
    links_.push_back({&link, pose, on_chassis});
    for (std::size_t k = 0; k < link.child_links.size(); ++k) {
      const urdf::Joint& j = *link.child_joints[k];
      const urdf::Link& child = *link.child_links[k];
      Visit(child, pose * ToEigen(j.parent_to_joint_origin_transform),
            on_chassis && j.type == urdf::Joint::FIXED);
    }
  }
  std::vector<Placed> links_;
};

class RobotMapper {
 public:
  RobotMapper(std::string source, const UrdfRobotOptions& options, const urdf::ModelInterface& m,
              const std::string& text)
      : source_(std::move(source)), options_(options), model_(m), text_(text), tree_(m) {}

  UrdfRobot Map() {
    MassAndCentre();
    Wheels();
    Chassis();
    Camera();
    Sensors();
    Unmapped();
    UrdfRobot& o = out_;
    for (double* v : {&o.mass_kg, &o.com_height_m, &o.ground_clearance_m, &o.track_gauge_m,
                      &o.track_width_m, &o.sprocket_radius_m}) {
      *v = Rounded(*v);
    }
    o.hull_size_m = Rounded(o.hull_size_m);
    for (double& x : o.station_x_m) x = Rounded(x);
    if (o.track_contact_length_m) o.track_contact_length_m = Rounded(*o.track_contact_length_m);
    if (o.camera_mount_m) o.camera_mount_m = Rounded(*o.camera_mount_m);
    if (o.camera_pitch_down_deg) o.camera_pitch_down_deg = Rounded(*o.camera_pitch_down_deg);
    if (CameraSensorMapping* c = o.sensors.camera ? &*o.sensors.camera : nullptr) {
      c->mount_m = Rounded(c->mount_m);
      c->pitch_down_deg = Rounded(c->pitch_down_deg);
      c->hfov_deg = Rounded(c->hfov_deg);
      if (c->baseline_m) c->baseline_m = Rounded(*c->baseline_m);
    }
    if (o.sensors.range) o.sensors.range->mount_m = Rounded(o.sensors.range->mount_m);
    return out_;
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    throw DescriptionError(source_ + ": robot '" + model_.getName() + "': " + what);
  }

  void MassAndCentre() {
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (const RobotTree::Placed& p : tree_.links()) {
      if (!p.link->inertial) continue;
      out_.mass_kg += p.link->inertial->mass;
      moment += p.link->inertial->mass * (p.pose * ToEigen(p.link->inertial->origin)).translation();
    }
    if (!(out_.mass_kg > 0.0)) Fail("no link has an <inertial><mass>: the robot's mass is needed");
    com_ = moment / out_.mass_kg;
  }

  void Wheels() {
    std::vector<Wheel> wheels;
    for (const RobotTree::Placed& p : tree_.links()) {
      const urdf::JointConstSharedPtr j = p.link->parent_joint;
      if (!j || (j->type != urdf::Joint::CONTINUOUS && j->type != urdf::Joint::REVOLUTE)) continue;
      const urdf::Cylinder* c = CylinderOf(*p.link);
      if (c == nullptr) continue;
      wheels.push_back({p.link->name, p.pose.translation(), c->radius, c->length,
                        Contains(p.link->name, "sprocket")});
    }
    out_.tracks =
        std::any_of(wheels.begin(), wheels.end(), [](const Wheel& w) { return w.sprocket; });
    std::vector<double> left, right;
    double left_y = 0.0, right_y = 0.0, ground_z = 0.0, road_radius = 0.0;
    int ground_n = 0;
    for (const Wheel& w : wheels) {
      if (w.sprocket) {
        out_.sprocket_radius_m = w.radius;
        continue;
      }
      (w.center.y() > 0.0 ? left : right).push_back(w.center.x());
      (w.center.y() > 0.0 ? left_y : right_y) += w.center.y();
      if (!out_.tracks) out_.sprocket_radius_m = w.radius;
      out_.track_width_m = w.width;
      road_radius = w.radius;
      ground_z += w.center.z() - w.radius;
      ++ground_n;
    }
    if (left.size() < 2 || left.size() != right.size()) {
      Fail(
          "wheels must come in left-right pairs, at least two a side (continuous or revolute "
          "joints whose child link has a cylinder; found " +
          std::to_string(left.size()) + " left, " + std::to_string(right.size()) + " right)");
    }
    std::sort(left.begin(), left.end());
    std::sort(right.begin(), right.end());
    for (std::size_t k = 0; k < left.size(); ++k) {
      if (std::abs(left[k] - right[k]) > kPairM) {
        Fail("the left and right wheels are not at the same stations along x (" +
             std::to_string(left[k]) + " and " + std::to_string(right[k]) + " m)");
      }
      out_.station_x_m.push_back(left[k] - com_.x());
    }
    // Under a track the ground run reaches from the rear road wheel's rim to the front's.
    if (out_.tracks) out_.track_contact_length_m = left.back() - left.front() + 2.0 * road_radius;
    out_.track_gauge_m = left_y / left.size() - right_y / right.size();
    ground_z_ = ground_z / ground_n;
    out_.com_height_m = com_.z() - ground_z_;
  }

  void Chassis() {
    for (const RobotTree::Placed& p : tree_.links()) {
      if (!p.on_chassis) continue;
      for (const urdf::CollisionSharedPtr& c : p.link->collision_array) {
        if (!c || !c->geometry || c->geometry->type != urdf::Geometry::BOX) continue;
        const urdf::Vector3 d = static_cast<const urdf::Box*>(c->geometry.get())->dim;
        out_.hull_size_m = Eigen::Vector3d(d.x, d.y, d.z);
        const double centre_z = (p.pose * ToEigen(c->origin)).translation().z();
        out_.ground_clearance_m = centre_z - 0.5 * d.z - ground_z_;
        return;
      }
    }
    Fail("no <collision> with a <box> on the chassis (the root link '" + model_.getRoot()->name +
         "' and the links fixed to it): the hull's box is needed");
  }

  void Camera() {
    const RobotTree::Placed* camera = nullptr;
    for (const RobotTree::Placed& p : tree_.links()) {
      const std::string& n = p.link->name;
      const bool named = options_.camera_link.empty()
                             ? Contains(n, "camera") && !Contains(n, "optical")
                             : n == options_.camera_link;
      if (named && camera == nullptr) camera = &p;
    }
    if (camera == nullptr) {
      if (!options_.camera_link.empty())
        Fail("no link '" + options_.camera_link + "' (camera_link)");
      return;
    }
    const Eigen::Matrix3d& r = camera->pose.linear();
    out_.camera_mount_m = camera->pose.translation() - com_;
    out_.camera_pitch_down_deg = std::asin(std::clamp(-r(2, 0), -1.0, 1.0)) * kDegPerRad;
    const double roll = std::atan2(r(2, 1), r(2, 2)), yaw = std::atan2(r(1, 0), r(0, 0));
    if (std::abs(roll) > kTurnRad || std::abs(yaw) > kTurnRad) {
      out_.unmapped.push_back("link '" + camera->link->name + "': the camera's roll " +
                              std::to_string(roll * kDegPerRad) + " deg and yaw " +
                              std::to_string(yaw * kDegPerRad) +
                              " deg: robot.stereo has no key for them (only the pitch is mapped)");
    }
    if (!camera->on_chassis) {
      out_.unmapped.push_back("link '" + camera->link->name +
                              "': mounted through a moving joint; taken at the joint's zero");
    }
  }

  // The <gazebo reference="LINK"> blocks' sensors, each at its link's frame.
  void Sensors() {
    for (const GazeboSensorText& g : GazeboSensors(text_)) {
      const std::string where = source_ + ": <gazebo reference=\"" + g.link + "\"> <sensor>";
      const RobotTree::Placed* link = nullptr;
      for (const RobotTree::Placed& p : tree_.links()) {
        if (p.link->name == g.link) link = &p;
      }
      if (link == nullptr) {
        out_.unmapped.push_back(where + ": no link '" + g.link +
                                "' to mount it on (a sensor block names its link)");
        continue;
      }
      MapSensorText(g.xml, where, link->pose, com_, &out_.sensors, &out_.unmapped);
    }
    if (out_.sensors.camera) {
      out_.camera_mount_m = out_.sensors.camera->mount_m;
      out_.camera_pitch_down_deg = out_.sensors.camera->pitch_down_deg;
    }
  }

  void Unmapped() {
    out_.unmapped.push_back(
        "the links' inertia tensors: robot.vehicle takes the mass, the box "
        "and the centre of mass only");
    for (const RobotTree::Placed& p : tree_.links()) {
      if (Contains(p.link->name, "imu")) {
        out_.unmapped.push_back("link '" + p.link->name +
                                "': the IMU's mount has no key (robot.imu "
                                "sits at the centre of mass)");
      }
      const urdf::JointConstSharedPtr j = p.link->parent_joint;
      if (j && j->type != urdf::Joint::FIXED && j->type != urdf::Joint::CONTINUOUS &&
          j->type != urdf::Joint::REVOLUTE) {
        out_.unmapped.push_back("joint '" + j->name +
                                "': only fixed joints and wheels' turning "
                                "joints are mapped");
      }
    }
  }

  std::string source_;
  const UrdfRobotOptions& options_;
  const urdf::ModelInterface& model_;
  const std::string& text_;
  RobotTree tree_;
  UrdfRobot out_;
  Eigen::Vector3d com_ = Eigen::Vector3d::Zero();
  double ground_z_ = 0.0;
};

}  // namespace

UrdfRobot ReadUrdfRobotString(const std::string& urdf_text, const std::string& source_name,
                              const UrdfRobotOptions& options) {
  urdf::ModelInterfaceSharedPtr model;
  std::string messages;
  {
    CapturedMessages captured;
    model = urdf::parseURDF(urdf_text);
    messages = captured.text();
  }
  if (!model) {
    throw DescriptionError(source_name + ": not a URDF robot urdfdom can read" +
                           (messages.empty() ? std::string() : ": " + messages));
  }
  return RobotMapper(source_name, options, *model, urdf_text).Map();
}

UrdfRobot ReadUrdfRobot(const UrdfRobotOptions& options) {
  std::ifstream in(options.file, std::ios::binary);
  if (!std::filesystem::is_regular_file(options.file) || !in) {
    throw DescriptionError(options.file + ": no such file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (text.str().find("xmlns:xacro") != std::string::npos ||
      text.str().find("<xacro:") != std::string::npos) {
    throw DescriptionError(options.file +
                           ": a xacro file; expand it first (xacro robot.urdf.xacro > robot.urdf)");
  }
  return ReadUrdfRobotString(text.str(), options.file, options);
}

}  // namespace trackbed::description
