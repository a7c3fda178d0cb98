// Gazebo sensor blocks through sdformat, mapped onto robot.stereo and
// robot.range_sensor (see sensor_reading.h and docs/gazebo_users.md, "Sensors").
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <tinyxml.h>
#include <sdf/Camera.hh>
#include <sdf/Console.hh>
#include <sdf/Error.hh>
#include <sdf/Lidar.hh>
#include <sdf/Link.hh>
#include <sdf/Model.hh>
#include <sdf/Noise.hh>
#include <sdf/ParserConfig.hh>
#include <sdf/Root.hh>
#include <sdf/Sensor.hh>

#include "sensor_reading.h"
#include "trackbed/description/description_error.h"

namespace trackbed::description {

namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr double kSensorTurnRad = 1e-9;  // a sensor's roll or yaw taken as none [rad]
constexpr unsigned kMaxBeams = 1000000;  // a scan's beams at most (the range sensor's memory)
constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

Eigen::Isometry3d SensorPose(const ignition::math::Pose3d& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(p.Rot().W(), p.Rot().X(), p.Rot().Y(), p.Rot().Z())
                   .normalized()
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.Pos().X(), p.Pos().Y(), p.Pos().Z());
  return t;
}

std::string Number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A Gaussian noise's standard deviation (times `scale`); its mean and other kinds listed.
std::optional<double> GaussianStd(const sdf::Noise& noise, double scale, const std::string& where,
                                  std::vector<std::string>* unmapped) {
  if (noise.Type() == sdf::NoiseType::NONE) return std::nullopt;
  if (noise.Type() != sdf::NoiseType::GAUSSIAN &&
      noise.Type() != sdf::NoiseType::GAUSSIAN_QUANTIZED) {
    unmapped->push_back(where + " <noise>: only Gaussian noise has a key");
    return std::nullopt;
  }
  if (noise.Mean() != 0.0 || noise.BiasMean() != 0.0 || noise.BiasStdDev() != 0.0) {
    unmapped->push_back(where + " <noise>: a mean or bias has no key (only the stddev is mapped)");
  }
  return noise.StdDev() * scale;
}

// The sensor element's own children that no key takes, listed when the file sets them.
void ListSet(const sdf::ElementPtr& e, const std::vector<const char*>& names,
             const std::string& where, const std::string& why, std::vector<std::string>* unmapped) {
  for (const char* name : names) {
    if (e && e->HasElement(name) && e->GetElement(name)->GetExplicitlySetInFile()) {
      unmapped->push_back(where + " <" + name + ">: " + why);
    }
  }
}

// The camera's frame (x along the view) as robot.stereo's mount and pitch.
void SetMount(const Eigen::Isometry3d& T_root_camera, const Eigen::Vector3d& com,
              const std::string& where, CameraSensorMapping* c,
              std::vector<std::string>* unmapped) {
  const Eigen::Matrix3d& r = T_root_camera.linear();
  c->mount_m = T_root_camera.translation() - com;
  c->pitch_down_deg = std::asin(std::clamp(-r(2, 0), -1.0, 1.0)) * kDegreesPerRadian;
  const double roll = std::atan2(r(2, 1), r(2, 2)), yaw = std::atan2(r(1, 0), r(0, 0));
  if (std::abs(roll) > kSensorTurnRad || std::abs(yaw) > kSensorTurnRad) {
    unmapped->push_back(where + ": the camera's roll " + Number(roll * kDegreesPerRadian) +
                        " deg and yaw " + Number(yaw * kDegreesPerRadian) +
                        " deg: robot.stereo has no key for them (only the pitch is mapped)");
  }
}

// One camera's image, view and noise.
CameraSensorMapping CameraOf(const sdf::Camera& cam, const std::string& where,
                             std::vector<std::string>* unmapped) {
  CameraSensorMapping c;
  c.width_px = static_cast<int>(cam.ImageWidth());
  c.height_px = static_cast<int>(cam.ImageHeight());
  c.hfov_deg = cam.HorizontalFov().Degree();
  c.near_m = cam.NearClip();
  c.far_m = cam.FarClip();
  c.noise_std = GaussianStd(cam.ImageNoise(), 255.0, where, unmapped);
  const sdf::ElementPtr e = cam.Element();
  ListSet(e, {"distortion", "lens"}, where,
          "not mapped: robot.stereo.distortion is the realism profile's lens "
          "(docs/camera_model.md)",
          unmapped);
  ListSet(e, {"depth_camera", "save", "visibility_mask", "segmentation_type", "box_type"}, where,
          "has no key", unmapped);
  if (e && e->HasElement("image") && e->GetElement("image")->HasElement("format") &&
      e->GetElement("image")->GetElement("format")->GetExplicitlySetInFile()) {
    unmapped->push_back(where + " <image><format>: trackbed's cameras give grey images");
  }
  return c;
}

// The cameras of a multicamera block, each with its pose in the sensor's frame.
std::vector<std::pair<sdf::Camera, Eigen::Isometry3d>> Cameras(const sdf::Sensor& sensor,
                                                               const std::string& where) {
  std::vector<std::pair<sdf::Camera, Eigen::Isometry3d>> cameras;
  const sdf::ElementPtr e = sensor.Element();
  if (!e->HasElement("camera")) return cameras;
  for (sdf::ElementPtr c = e->GetElement("camera"); c; c = c->GetNextElement("camera")) {
    sdf::Camera camera;
    const sdf::Errors errors = camera.Load(c);
    if (!errors.empty()) throw DescriptionError(where + ": " + errors.front().Message());
    cameras.emplace_back(camera, SensorPose(camera.RawPose()));
  }
  return cameras;
}

void MapCamera(const sdf::Sensor& sensor, const std::string& where, const Eigen::Isometry3d& T,
               const Eigen::Vector3d& com, SensorBlocks* out, std::vector<std::string>* unmapped) {
  std::vector<std::pair<sdf::Camera, Eigen::Isometry3d>> cameras;
  if (sensor.Type() == sdf::SensorType::MULTICAMERA) {
    cameras = Cameras(sensor, where);
  } else if (sensor.CameraSensor() != nullptr) {
    cameras.emplace_back(*sensor.CameraSensor(), SensorPose(sensor.CameraSensor()->RawPose()));
  }
  if (cameras.empty()) throw DescriptionError(where + ": a camera sensor without a <camera>");
  CameraSensorMapping c = CameraOf(cameras[0].first, where, unmapped);
  c.name = sensor.Name();
  if (sensor.UpdateRate() > 0.0) {
    c.rate_hz = sensor.UpdateRate();
  } else {
    unmapped->push_back(where +
                        " <update_rate>: 0 (as fast as the simulation runs) has no key; "
                        "robot.stereo.rate_hz keeps its value");
  }
  const Eigen::Isometry3d T_left = T * cameras[0].second;
  SetMount(T_left, com, where, &c, unmapped);
  if (cameras.size() >= 2) {
    const Eigen::Isometry3d T_right = T * cameras[1].second;
    const Eigen::Vector3d d = T_left.inverse() * T_right.translation();  // in the left's frame
    c.baseline_m = d.norm();
    c.mount_m = 0.5 * (T_left.translation() + T_right.translation()) - com;
    if (std::abs(d.x()) > 1e-9 || std::abs(d.z()) > 1e-9 || d.y() > 0.0) {
      unmapped->push_back(where +
                          ": the second camera is not to the right of the first along "
                          "its y axis: taken as a rectified pair of baseline " +
                          Number(*c.baseline_m) + " m");
    }
    const CameraSensorMapping right = CameraOf(cameras[1].first, where, unmapped);
    if (right.width_px != c.width_px || right.height_px != c.height_px ||
        right.hfov_deg != c.hfov_deg) {
      unmapped->push_back(where +
                          ": the second camera's image or field of view differs from the "
                          "first's: both are taken as the first's");
    }
  }
  if (cameras.size() > 2) {
    unmapped->push_back(where + ": cameras after the second (robot.stereo is a pair)");
  }
  out->camera = c;
}

void MapRange(const sdf::Sensor& sensor, const std::string& where, const Eigen::Isometry3d& T,
              const Eigen::Vector3d& com, SensorBlocks* out, std::vector<std::string>* unmapped) {
  const sdf::Lidar* lidar = sensor.LidarSensor();
  if (lidar == nullptr) throw DescriptionError(where + ": a ray sensor without a <ray> or <lidar>");
  RangeSensorMapping r;
  r.name = sensor.Name();
  if (lidar->HorizontalScanSamples() > kMaxBeams) {
    throw DescriptionError(where + ": " + std::to_string(lidar->HorizontalScanSamples()) +
                           " samples, more than a million");
  }
  const int samples = static_cast<int>(lidar->HorizontalScanSamples());
  const double span =
      lidar->HorizontalScanMaxAngle().Radian() - lidar->HorizontalScanMinAngle().Radian();
  // Gazebo's samples run from the min angle to the max one, both included.
  const bool full_turn = samples >= 2 && span >= kTwoPi * (1.0 - 1.0 / samples);
  if (full_turn) {
    r.beams = samples;
  } else if (samples >= 2 && span > 0.0) {
    const double beams = kTwoPi * (samples - 1) / span;
    if (!(beams <= kMaxBeams)) {
      throw DescriptionError(where + ": the scan's spacing of " + Number(span / (samples - 1)) +
                             " rad would take more than a million beams over 360 deg");
    }
    r.beams = static_cast<int>(std::lround(beams));
    unmapped->push_back(
        where + ": the scan from " + Number(lidar->HorizontalScanMinAngle().Degree()) + " to " +
        Number(lidar->HorizontalScanMaxAngle().Degree()) +
        " deg is cast over 360 deg at its spacing (robot.range_sensor scans a full turn)");
  } else {
    r.beams = std::max(samples, 1);
    unmapped->push_back(where + ": a scan of " + std::to_string(samples) + " samples over " +
                        Number(span) + " rad has no spacing to keep");
  }
  if (lidar->HorizontalScanResolution() != 1.0) {
    unmapped->push_back(where + " <resolution>: the samples are not interpolated");
  }
  if (lidar->VerticalScanSamples() > 1) {
    unmapped->push_back(where + " <vertical>: " + std::to_string(lidar->VerticalScanSamples()) +
                        " rows; robot.range_sensor is planar (the row at zero elevation)");
  }
  r.min_range_m = lidar->RangeMin();
  r.max_range_m = lidar->RangeMax();
  r.noise_std_m = GaussianStd(lidar->LidarNoise(), 1.0, where, unmapped);
  if (sensor.UpdateRate() > 0.0) {
    r.rate_hz = sensor.UpdateRate();
  } else {
    unmapped->push_back(where +
                        " <update_rate>: 0 has no key; robot.range_sensor.rate_hz keeps "
                        "its value");
  }
  r.mount_m = T.translation() - com;
  if (!T.linear().isIdentity(1e-9)) {
    unmapped->push_back(where + ": a turned scanner: robot.range_sensor's axes are the body's");
  }
  out->range = r;
}

}  // namespace

std::vector<GazeboSensorText> GazeboSensors(const std::string& urdf_text) {
  std::vector<GazeboSensorText> found;
  TiXmlDocument doc;
  doc.Parse(urdf_text.c_str());
  if (doc.Error()) return found;
  const TiXmlElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) return found;
  for (const TiXmlElement* g = robot->FirstChildElement("gazebo"); g;
       g = g->NextSiblingElement("gazebo")) {
    const char* reference = g->Attribute("reference");
    for (const TiXmlElement* s = g->FirstChildElement("sensor"); s;
         s = s->NextSiblingElement("sensor")) {
      std::string xml;
      xml << *s;
      found.push_back({reference ? reference : "", xml});
    }
  }
  return found;
}

void MapSensorText(const std::string& xml, const std::string& where,
                   const Eigen::Isometry3d& T_root_frame, const Eigen::Vector3d& com_root,
                   SensorBlocks* out, std::vector<std::string>* unmapped) {
  sdf::Console::Instance()->SetQuiet(true);
  sdf::Root root;
  const sdf::Errors errors = root.LoadSdfString(
      "<?xml version='1.0'?><sdf version='1.6'><model name='robot'><link name='link'>" + xml +
          "</link></model></sdf>",
      sdf::ParserConfig());
  if (!errors.empty()) throw DescriptionError(where + ": " + errors.front().Message());
  const sdf::Model* model = root.Model();
  if (model == nullptr || model->LinkCount() == 0 || model->LinkByIndex(0)->SensorCount() == 0) {
    throw DescriptionError(where + ": not a <sensor> sdformat reads");
  }
  const sdf::Sensor& sensor = *model->LinkByIndex(0)->SensorByIndex(0);
  const Eigen::Isometry3d T = T_root_frame * SensorPose(sensor.RawPose());
  switch (sensor.Type()) {
    case sdf::SensorType::CAMERA:
    case sdf::SensorType::MULTICAMERA:
      if (out->camera) break;
      MapCamera(sensor, where, T, com_root, out, unmapped);
      return;
    case sdf::SensorType::LIDAR:
    case sdf::SensorType::GPU_LIDAR:
      if (out->range) break;
      MapRange(sensor, where, T, com_root, out, unmapped);
      return;
    case sdf::SensorType::IMU:
      unmapped->push_back(where +
                          ": an IMU block: robot.imu is the part its keys name, at the "
                          "centre of mass");
      return;
    default:
      unmapped->push_back(where + ": a '" + sensor.TypeStr() +
                          "' sensor has no counterpart in trackbed");
      return;
  }
  unmapped->push_back(where + ": a second " + sensor.TypeStr() +
                      " sensor (the first one is mapped)");
}

}  // namespace trackbed::description
