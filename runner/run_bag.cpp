// A run folder as a ROS 2 bag (see run_bag.h). Each topic is a stream of rows read
// from one of the folder's files; the streams are merged by time (ties in topic order)
// and each message is serialised as it is written, so memory holds the rows, not the
// messages.
#include "trackbed/runner/run_bag.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/common/robot_calibration.h"
#include "trackbed/estimation/trajectory_io.h"
#include "trackbed/perception/stereo_rectifier.h"
#include "trackbed/recording/mcap_writer.h"
#include "trackbed/recording/ros2_messages.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {
namespace {

namespace fs = std::filesystem;
namespace rec = recording;

// A CSV file of numbers with a header row (the run folder's form).
struct CsvTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;

  std::size_t Column(const fs::path& file, const std::string& name) const {
    const auto it = std::find(columns.begin(), columns.end(), name);
    if (it == columns.end()) throw std::runtime_error(file.string() + ": no column " + name);
    return static_cast<std::size_t>(it - columns.begin());
  }
};

std::vector<std::string> SplitComma(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string field; std::getline(s, field, ',');) out.push_back(field);
  return out;
}

CsvTable ReadCsv(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot open");
  CsvTable t;
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(file.string() + ": empty, no header row");
  t.columns = SplitComma(line);
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::vector<std::string> fields = SplitComma(line);
    if (fields.size() != t.columns.size()) {
      throw std::runtime_error(file.string() + ":" + std::to_string(number) + ": " +
                               std::to_string(fields.size()) + " fields, the header has " +
                               std::to_string(t.columns.size()));
    }
    std::vector<double> row;
    for (const std::string& f : fields) {
      char* end = nullptr;
      row.push_back(std::strtod(f.c_str(), &end));
      if (f.empty() || *end != '\0') {
        throw std::runtime_error(file.string() + ":" + std::to_string(number) +
                                 ": not a number: '" + f + "'");
      }
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

rec::Pose ToPose(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  return {{T.translation().x(), T.translation().y(), T.translation().z()},
          {q.x(), q.y(), q.z(), q.w()}};
}

rec::Header At(double t_s, const std::string& frame) {
  return {rec::Time::FromSeconds(t_s), frame};
}

// rosbag2's offered QoS profile of a recorded publisher (rmw enum values: history
// unknown 3, reliability reliable 1, durability transient-local 1 or volatile 2,
// liveliness automatic 1; infinite durations), as the channel metadata and
// metadata.yaml carry it.
std::string QosProfile(bool transient_local) {
  const char* infinite = "\n    sec: 9223372036\n    nsec: 854775807";
  std::string q = "- history: 3\n  depth: 0\n  reliability: 1\n  durability: ";
  q += transient_local ? "1" : "2";
  q += std::string("\n  deadline:") + infinite + "\n  lifespan:" + infinite +
       "\n  liveliness: 1\n  liveliness_lease_duration:" + infinite +
       "\n  avoid_ros_namespace_conventions: false";
  return q;
}

// One topic: its channel, its messages' times and how to serialise the k-th.
struct Stream {
  std::string topic, type, definition;
  bool transient_local = false;
  std::vector<double> t_s;
  std::function<std::vector<std::uint8_t>(std::size_t)> message;
  std::uint16_t channel = 0;
};

template <typename M>
Stream MakeStream(const std::string& topic, std::vector<double> t_s,
                  std::function<M(std::size_t)> build, bool transient_local = false) {
  const rec::MessageSchema& schema = rec::SchemaOf(M{});
  Stream s{topic, schema.name, schema.definition, transient_local, std::move(t_s), nullptr, 0};
  s.message = [build = std::move(build)](std::size_t k) { return rec::Serialize(build(k)); };
  return s;
}

using Poses = std::shared_ptr<const estimation::Trajectory>;

Poses ReadTum(const fs::path& tum) {
  return std::make_shared<const estimation::Trajectory>(
      estimation::ReadTrajectory(tum, estimation::TrajectoryFormat::kTum).poses);
}

std::vector<double> TimesOf(const estimation::Trajectory& poses) {
  std::vector<double> t;
  for (const auto& p : poses) t.push_back(p.t_s);
  return t;
}

// An estimate's (or the ground truth's) poses as Odometry; `twist` (rows as the poses)
// may be empty.
Stream OdometryStream(const std::string& topic, Poses poses, const std::string& frame,
                      const std::string& child, std::shared_ptr<const CsvTable> twist) {
  return MakeStream<rec::Odometry>(topic, TimesOf(*poses), [=](std::size_t k) {
    rec::Odometry o;
    o.header = At((*poses)[k].t_s, frame);
    o.child_frame_id = child;
    o.pose = ToPose((*poses)[k].T_world_body);
    if (twist) {
      const std::vector<double>& r = twist->rows[k];
      o.linear = {r[1], r[2], r[3]};
      o.angular = {r[4], r[5], r[6]};
    }
    return o;
  });
}

// The estimate files of a run folder, and the topic name of each (`<name>.tum` gives
// `/<name>/odom`; the ground truth has its own).
std::vector<std::string> EstimateNames(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const fs::path p = entry.path();
    if (p.extension() == ".tum" && p.stem() != "ground_truth") names.push_back(p.stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

Stream ClockStream(const std::vector<double>& t) {
  return MakeStream<rec::Clock>(
      "/clock", t, [t](std::size_t k) { return rec::Clock{rec::Time::FromSeconds(t[k])}; });
}

// /tf: map → odom, the identity (this stack has no map), and odom → base_link from the
// fused estimate, at its rate.
Stream TfStream(Poses poses) {
  return MakeStream<rec::TFMessage>("/tf", TimesOf(*poses), [poses](std::size_t k) {
    const double t_s = (*poses)[k].t_s;
    return rec::TFMessage{{{At(t_s, "map"), "odom", rec::Pose{}},
                           {At(t_s, "odom"), "base_link", ToPose((*poses)[k].T_world_body)}}};
  });
}

Stream ImuStream(const fs::path& file) {
  auto imu = std::make_shared<const CsvTable>(ReadCsv(file));
  std::array<std::size_t, 7> c;  // t, then the gyro's and the accelerometer's x, y, z
  const char* names[] = {
      "t",           "gyro_x_radps", "gyro_y_radps", "gyro_z_radps", "accel_x_mps2", "accel_y_mps2",
      "accel_z_mps2"};
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = imu->Column(file, names[i]);
  std::vector<double> t;
  for (const auto& r : imu->rows) t.push_back(r[c[0]]);
  return MakeStream<rec::Imu>("/imu", t, [imu, c](std::size_t k) {
    const std::vector<double>& r = imu->rows[k];
    rec::Imu m;
    m.header = At(r[c[0]], "imu_link");
    m.orientation_covariance[0] = -1.0;  // no orientation estimate (REP-145)
    m.angular_velocity = {r[c[1]], r[c[2]], r[c[3]]};
    m.linear_acceleration = {r[c[4]], r[c[5]], r[c[6]]};
    return m;
  });
}

// The sprockets' angles from the encoder counts, and their rates as the backward
// difference of the counts (what the wheel odometry sees).
Stream JointStream(const fs::path& file, int ticks_per_rev) {
  auto enc = std::make_shared<const CsvTable>(ReadCsv(file));
  enc->Column(file, "left_ticks");
  enc->Column(file, "right_ticks");
  std::vector<double> t;
  for (const auto& r : enc->rows) t.push_back(r[0]);
  const double rad_per_tick = 2.0 * M_PI / ticks_per_rev;
  return MakeStream<rec::JointState>("/joint_states", t, [enc, rad_per_tick](std::size_t k) {
    const std::vector<double>& r = enc->rows[k];
    rec::JointState j;
    j.header = At(r[0], "");
    j.name = {"left_sprocket_joint", "right_sprocket_joint"};
    j.position = {r[1] * rad_per_tick, r[2] * rad_per_tick};
    j.velocity = {0.0, 0.0};
    if (k > 0) {
      const std::vector<double>& p = enc->rows[k - 1];
      const double dt = r[0] - p[0];
      if (dt > 0)
        j.velocity = {(r[1] - p[1]) * rad_per_tick / dt, (r[2] - p[2]) * rad_per_tick / dt};
    }
    return j;
  });
}

// /scan from scan.csv: the beams fan counter-clockwise from straight ahead over a full
// turn, all taken at the scan's time (the simulated sensor does not spin during a
// scan), +inf where no return (REP-117).
Stream ScanStream(const fs::path& file, const robot::RangeSensorOptions& sensor) {
  auto scans = std::make_shared<const CsvTable>(ReadCsv(file));
  const std::size_t beams = static_cast<std::size_t>(sensor.beams);
  if (scans->columns.size() != beams + 1) {
    throw std::runtime_error(file.string() + ": " + std::to_string(scans->columns.size() - 1) +
                             " ranges per row, the scenario's range sensor has " +
                             std::to_string(beams) + " beams");
  }
  std::vector<double> t;
  for (const auto& r : scans->rows) t.push_back(r[0]);
  rec::LaserScan shape;
  shape.angle_increment = static_cast<float>(2.0 * M_PI / sensor.beams);
  shape.angle_max = static_cast<float>(2.0 * M_PI * (sensor.beams - 1) / sensor.beams);
  shape.scan_time = static_cast<float>(1.0 / sensor.rate_hz);
  shape.range_min = static_cast<float>(sensor.min_range_m);
  shape.range_max = static_cast<float>(sensor.max_range_m);
  return MakeStream<rec::LaserScan>("/scan", t, [scans, shape](std::size_t k) {
    const std::vector<double>& r = scans->rows[k];
    rec::LaserScan m = shape;
    m.header = At(r[0], "range_sensor");
    m.ranges.assign(r.begin() + 1, r.end());
    return m;
  });
}

// /tf_static, once at the start: the cameras' optical frames (OpenCV axes, REP-103's
// `_optical`) and the IMU's axes, as the calibration the stack was given has them (the
// IMU's file gives no position: its origin is the body's), and the range sensor's mount.
Stream StaticTfStream(const calibration::RobotCalibration& given,
                      const scenario::Scenario& scenario) {
  rec::TFMessage m;
  const auto add = [&](const std::string& child, const Eigen::Isometry3d& T) {
    m.transforms.push_back({At(0.0, "base_link"), child, ToPose(T)});
  };
  if (given.stereo) {
    add("left_camera_optical", given.stereo->T_body_left);
    add("right_camera_optical", given.stereo->T_body_right);
  }
  Eigen::Isometry3d T_body_imu = Eigen::Isometry3d::Identity();
  T_body_imu.linear() = given.imu.R_body_imu;
  add("imu_link", T_body_imu);
  if (scenario.robot.range_sensor.enabled) {
    add("range_sensor",
        Eigen::Isometry3d(Eigen::Translation3d(scenario.robot.range_sensor.mount_m)));
  }
  return MakeStream<rec::TFMessage>(
      "/tf_static", {0.0}, [m](std::size_t) { return m; }, true);
}

// camera_info of one camera (0 left, 1 right), latched at the start: K and D the
// given calibration's, R and P the rectification the stack computes from it (OpenCV's
// stereoRectify, alpha 0), P of the right camera carrying −fx·baseline.
rec::CameraInfo CameraInfoOf(const calibration::StereoCalibration& given,
                             const perception::StereoRectifier& rectifier, int camera) {
  const calibration::CameraIntrinsics& k = camera == 0 ? given.left : given.right;
  rec::CameraInfo c;
  c.header = At(0.0, camera == 0 ? "left_camera_optical" : "right_camera_optical");
  c.width = static_cast<std::uint32_t>(given.width_px);
  c.height = static_cast<std::uint32_t>(given.height_px);
  c.k = {k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1};
  const geometry::LensDistortion lens = k.Lens();
  if (lens.model == geometry::LensModel::kEquidistant) {
    c.distortion_model = "equidistant";
    c.d = {lens.k1, lens.k2, lens.k3, lens.k4};
  } else {
    c.distortion_model = "plumb_bob";
    c.d = {lens.k1, lens.k2, lens.p1, lens.p2, lens.k3};
  }
  const geometry::PinholeCamera& r = rectifier.camera().left;
  const Eigen::Matrix3d R_body_camera =
      (camera == 0 ? given.T_body_left : given.T_body_right).linear();
  const Eigen::Matrix3d R = rectifier.T_body_left().linear().transpose() * R_body_camera;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) c.r[3 * i + j] = R(i, j);
  }
  const double tx = camera == 0 ? 0.0 : -r.fx * rectifier.camera().baseline_m;
  c.p = {r.fx, 0, r.cx, tx, 0, r.fy, r.cy, 0, 0, 0, 1, 0};
  return c;
}

// camera/times.txt: one time [s] per line.
std::vector<double> ReadTimes(const fs::path& file) {
  std::ifstream in(file);
  std::vector<double> t;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    char* end = nullptr;
    t.push_back(std::strtod(line.c_str(), &end));
    if (line.empty() || *end != '\0') {
      throw std::runtime_error(file.string() + ":" + std::to_string(number) + ": not a time: '" +
                               line + "'");
    }
  }
  return t;
}

std::vector<std::uint8_t> ReadBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) throw std::runtime_error(file.string() + ": cannot open");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(in.tellg()));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()))) {
    throw std::runtime_error(file.string() + ": cannot read");
  }
  return bytes;
}

// One camera's topics: with the frames saved (camera/), its images as PNG and a
// camera_info per frame, stamped alike; without, camera_info once, latched.
void AddCameraStreams(const rec::CameraInfo& info, int c, const fs::path& camera,
                      const std::vector<double>& frames, std::vector<Stream>* streams) {
  const std::string side = c == 0 ? "left" : "right";
  if (frames.empty()) {
    streams->push_back(MakeStream<rec::CameraInfo>(
        "/stereo/" + side + "/camera_info", {0.0}, [info](std::size_t) { return info; }, true));
    return;
  }
  streams->push_back(MakeStream<rec::CompressedImage>(
      "/stereo/" + side + "/image_raw/compressed", frames,
      [frames, info, dir = camera / side](std::size_t k) {
        char name[16];
        std::snprintf(name, sizeof(name), "%06zu.png", k);
        return rec::CompressedImage{At(frames[k], info.header.frame_id), "png",
                                    ReadBytes(dir / name)};
      }));
  streams->push_back(MakeStream<rec::CameraInfo>(
      "/stereo/" + side + "/camera_info", frames, [frames, info](std::size_t k) {
        rec::CameraInfo i = info;
        i.header.stamp = rec::Time::FromSeconds(frames[k]);
        return i;
      }));
}

// rosbag2's metadata.yaml (version 5, which ROS 2 Humble and later read) for one MCAP
// file holding every topic.
std::string MetadataYaml(const std::vector<Stream>& streams,
                         const std::map<std::string, std::uint64_t>& counts, std::uint64_t start_ns,
                         std::uint64_t end_ns, std::uint64_t total) {
  std::ostringstream y;
  y << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n"
    << "  duration:\n    nanoseconds: " << end_ns - start_ns << "\n"
    << "  starting_time:\n    nanoseconds_since_epoch: " << start_ns << "\n"
    << "  message_count: " << total << "\n  topics_with_message_count:\n";
  for (const Stream& s : streams) {
    std::string qos = QosProfile(s.transient_local), indented;
    for (char ch : qos) indented += ch == '\n' ? std::string("\n        ") : std::string(1, ch);
    y << "    - topic_metadata:\n        name: " << s.topic << "\n        type: " << s.type
      << "\n        serialization_format: cdr\n        offered_qos_profiles: |\n        "
      << indented << "\n      message_count: " << counts.at(s.topic) << "\n";
  }
  y << "  compression_format: \"\"\n  compression_mode: \"\"\n"
    << "  relative_file_paths:\n    - run.mcap\n  files:\n    - path: run.mcap\n"
    << "      starting_time:\n        nanoseconds_since_epoch: " << start_ns << "\n"
    << "      duration:\n        nanoseconds: " << end_ns - start_ns << "\n"
    << "      message_count: " << total << "\n";
  return y.str();
}

// The topics a run folder holds, in the bag's channel order.
std::vector<Stream> RunStreams(const fs::path& dir, const scenario::Scenario& scenario) {
  std::vector<Stream> streams;
  const bool physics = fs::exists(dir / "encoders.csv");
  const Poses gt = ReadTum(dir / "ground_truth.tum");
  streams.push_back(ClockStream(TimesOf(*gt)));
  std::map<std::string, Poses> estimates;  // each file read once
  for (const std::string& name : EstimateNames(dir))
    estimates[name] = ReadTum(dir / (name + ".tum"));
  if (estimates.count("fused")) streams.push_back(TfStream(estimates["fused"]));
  std::shared_ptr<const CsvTable> twist;
  if (physics) {
    const fs::path file = dir / "ground_truth_twist.csv";
    twist = std::make_shared<const CsvTable>(ReadCsv(file));
    if (twist->rows.size() != gt->size()) {
      throw std::runtime_error(file.string() + ": " + std::to_string(twist->rows.size()) +
                               " rows, ground_truth.tum has " + std::to_string(gt->size()));
    }
  }
  streams.push_back(
      OdometryStream("/ground_truth/odom", gt, "map", "base_link_ground_truth", twist));
  for (const auto& [name, poses] : estimates) {
    streams.push_back(OdometryStream("/" + name + "/odom", poses, "odom",
                                     name == "fused" ? "base_link" : "base_link_" + name, nullptr));
  }
  if (!physics) return streams;
  streams.push_back(ImuStream(dir / "imu.csv"));
  streams.push_back(JointStream(dir / "encoders.csv", scenario.robot.encoders.ticks_per_rev));
  const bool has_camera = fs::exists(dir / calibration::kStereoFile);
  const calibration::RobotCalibration given = calibration::ReadCalibrationFolder(dir, has_camera);
  streams.push_back(StaticTfStream(given, scenario));
  if (scenario.robot.range_sensor.enabled && fs::exists(dir / "scan.csv")) {  // older runs lack it
    streams.push_back(ScanStream(dir / "scan.csv", scenario.robot.range_sensor));
  }
  if (given.stereo) {
    const fs::path camera = dir / "camera";
    const std::vector<double> frames =
        fs::exists(camera / "times.txt") ? ReadTimes(camera / "times.txt") : std::vector<double>{};
    const perception::StereoRectifier rectifier(*given.stereo);  // the maps built once
    for (int c = 0; c < 2; ++c) {
      AddCameraStreams(CameraInfoOf(*given.stereo, rectifier, c), c, camera, frames, &streams);
    }
  }
  return streams;
}

}  // namespace

RunBagSummary WriteRunBag(const fs::path& dir) {
  // Read as a run driven from outside may have it: without a drive section.
  const scenario::Scenario scenario = scenario::LoadScenario((dir / "scenario.yaml").string(), {},
                                                             scenario::DriveSource::kExternal);
  std::vector<Stream> streams = RunStreams(dir, scenario);
  // Every message by time, ties in channel order then row order.
  struct Event {
    std::uint64_t t_ns;
    std::size_t stream, row;
  };
  std::vector<Event> events;
  for (std::size_t s = 0; s < streams.size(); ++s) {
    for (std::size_t k = 0; k < streams[s].t_s.size(); ++k) {
      events.push_back({rec::Time::FromSeconds(streams[s].t_s[k]).Nanoseconds(), s, k});
    }
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.t_ns < b.t_ns; });
  const fs::path file = dir / "run.mcap";
  rec::McapWriter writer(file.string());
  std::map<std::string, std::uint16_t> schemas;
  for (Stream& s : streams) {
    if (!schemas.count(s.type)) schemas[s.type] = writer.AddSchema(s.type, "ros2msg", s.definition);
    s.channel = writer.AddChannel(schemas[s.type], s.topic, "cdr",
                                  {{"offered_qos_profiles", QosProfile(s.transient_local)}});
  }
  for (const Event& e : events) {
    writer.Write(streams[e.stream].channel, e.t_ns, e.t_ns, streams[e.stream].message(e.row));
  }
  writer.Close();
  RunBagSummary summary;
  for (const Stream& s : streams) summary.messages_per_topic[s.topic] = s.t_s.size();
  summary.messages = events.size();
  const std::uint64_t start = events.empty() ? 0 : events.front().t_ns;
  const std::uint64_t end = events.empty() ? 0 : events.back().t_ns;
  std::ofstream yaml(dir / "metadata.yaml");
  yaml << MetadataYaml(streams, summary.messages_per_topic, start, end, summary.messages);
  if (!yaml.flush()) throw std::runtime_error((dir / "metadata.yaml").string() + ": write failed");
  return summary;
}

}  // namespace trackbed::runner
