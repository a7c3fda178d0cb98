// A run folder as a ROS 2 bag (see run_bag.h). Each topic is a stream of rows read
// one at a time from one of the folder's files; the streams are merged by time (ties in
// topic order, then row order) and each message is serialised as it is written, so
// memory holds one row and one message per topic, whatever the run's length.
#include "trackbed/runner/run_bag.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <queue>
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

std::vector<std::string> SplitComma(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string field; std::getline(s, field, ',');) out.push_back(field);
  return out;
}

// A CSV file of numbers with a header row (the run folder's form), read row by row.
class CsvReader {
 public:
  explicit CsvReader(const fs::path& file) : file_(file), in_(file) {
    if (!in_) throw std::runtime_error(file.string() + ": cannot open");
    std::string line;
    if (!std::getline(in_, line))
      throw std::runtime_error(file.string() + ": empty, no header row");
    columns_ = SplitComma(line);
  }
  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t Column(const std::string& name) const {
    const auto it = std::find(columns_.begin(), columns_.end(), name);
    if (it == columns_.end()) throw std::runtime_error(file_.string() + ": no column " + name);
    return static_cast<std::size_t>(it - columns_.begin());
  }
  /// The next row; false at the end.
  bool Next(std::vector<double>* row) {
    std::string line;
    do {
      if (!std::getline(in_, line)) return false;
      ++number_;
    } while (line.empty());
    const std::vector<std::string> fields = SplitComma(line);
    if (fields.size() != columns_.size()) {
      throw std::runtime_error(file_.string() + ":" + std::to_string(number_) + ": " +
                               std::to_string(fields.size()) + " fields, the header has " +
                               std::to_string(columns_.size()));
    }
    row->clear();
    for (const std::string& f : fields) {
      char* end = nullptr;
      row->push_back(std::strtod(f.c_str(), &end));
      if (f.empty() || *end != '\0') {
        throw std::runtime_error(file_.string() + ":" + std::to_string(number_) +
                                 ": not a number: '" + f + "'");
      }
    }
    return true;
  }

 private:
  fs::path file_;
  std::ifstream in_;
  std::vector<std::string> columns_;
  int number_ = 1;  // the header's line
};

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

// One topic: its channel and its messages, read one at a time: next(&t_s, &bytes) gives
// the next message's time and serialised bytes, false at the end.
struct Stream {
  std::string topic, type, definition;
  bool transient_local = false;
  std::function<bool(double*, std::vector<std::uint8_t>*)> next;
  std::uint16_t channel = 0;
  std::uint64_t count = 0;  // messages written
};

// A stream of messages M: `next(&t_s, &m)` builds the next one, false at the end.
template <typename M>
Stream MakeStream(const std::string& topic, std::function<bool(double*, M*)> next,
                  bool transient_local = false) {
  const rec::MessageSchema& schema = rec::SchemaOf(M{});
  Stream s{topic, schema.name, schema.definition, transient_local, nullptr, 0, 0};
  s.next = [next = std::move(next)](double* t_s, std::vector<std::uint8_t>* bytes) {
    M m;
    if (!next(t_s, &m)) return false;
    *bytes = rec::Serialize(m);
    return true;
  };
  return s;
}

// One message at time 0, as a latched topic has it.
template <typename M>
Stream OnceStream(const std::string& topic, M message) {
  auto done = std::make_shared<bool>(false);
  return MakeStream<M>(
      topic,
      [done, message](double* t_s, M* m) {
        if (*done) return false;
        *done = true;
        *t_s = 0.0;
        *m = message;
        return true;
      },
      true);
}

std::shared_ptr<estimation::TumReader> ReadTum(const fs::path& tum) {
  return std::make_shared<estimation::TumReader>(tum);
}

// The rows left in a CSV file and a TUM file (after a mismatch in their lengths).
std::size_t RowsLeft(CsvReader* csv) {
  std::size_t n = 0;
  for (std::vector<double> row; csv->Next(&row);) ++n;
  return n;
}
std::size_t PosesLeft(estimation::TumReader* tum) {
  std::size_t n = 0;
  for (estimation::StampedPose p; tum->Next(&p);) ++n;
  return n;
}

// An estimate's (or the ground truth's) poses as Odometry; `twist` (a row per pose, the
// ground truth's twist file) may be null.
Stream OdometryStream(const std::string& topic, const fs::path& tum, const std::string& frame,
                      const std::string& child, const fs::path& twist_file) {
  auto poses = ReadTum(tum);
  std::shared_ptr<CsvReader> twist;
  if (!twist_file.empty()) twist = std::make_shared<CsvReader>(twist_file);
  auto rows = std::make_shared<std::size_t>(0);
  return MakeStream<rec::Odometry>(topic, [=](double* t_s, rec::Odometry* o) {
    estimation::StampedPose p;
    const bool more = poses->Next(&p);
    std::vector<double> r;
    const bool more_twist = twist && twist->Next(&r);
    if (twist && more != more_twist) {  // the twist file has a row per true pose
      const std::size_t n_twist = *rows + (more_twist ? 1 + RowsLeft(twist.get()) : 0);
      const std::size_t n_poses = *rows + (more ? 1 + PosesLeft(poses.get()) : 0);
      throw std::runtime_error(twist_file.string() + ": " + std::to_string(n_twist) +
                               " rows, ground_truth.tum has " + std::to_string(n_poses));
    }
    if (!more) return false;
    ++*rows;
    *t_s = p.t_s;
    o->header = At(p.t_s, frame);
    o->child_frame_id = child;
    o->pose = ToPose(p.T_world_body);
    if (twist) {
      o->linear = {r[1], r[2], r[3]};
      o->angular = {r[4], r[5], r[6]};
    }
    return true;
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

// /clock at the ground truth's times.
Stream ClockStream(const fs::path& tum) {
  auto poses = ReadTum(tum);
  return MakeStream<rec::Clock>("/clock", [poses](double* t_s, rec::Clock* m) {
    estimation::StampedPose p;
    if (!poses->Next(&p)) return false;
    *t_s = p.t_s;
    *m = rec::Clock{rec::Time::FromSeconds(p.t_s)};
    return true;
  });
}

// /tf: map → odom, the identity (this stack has no map), and odom → base_link from the
// fused estimate, at its rate.
Stream TfStream(const fs::path& tum) {
  auto poses = ReadTum(tum);
  return MakeStream<rec::TFMessage>("/tf", [poses](double* t_s, rec::TFMessage* m) {
    estimation::StampedPose p;
    if (!poses->Next(&p)) return false;
    *t_s = p.t_s;
    *m = rec::TFMessage{{{At(p.t_s, "map"), "odom", rec::Pose{}},
                         {At(p.t_s, "odom"), "base_link", ToPose(p.T_world_body)}}};
    return true;
  });
}

Stream ImuStream(const fs::path& file) {
  auto imu = std::make_shared<CsvReader>(file);
  std::array<std::size_t, 7> c;  // t, then the gyro's and the accelerometer's x, y, z
  const char* names[] = {
      "t",           "gyro_x_radps", "gyro_y_radps", "gyro_z_radps", "accel_x_mps2", "accel_y_mps2",
      "accel_z_mps2"};
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = imu->Column(names[i]);
  return MakeStream<rec::Imu>("/imu", [imu, c](double* t_s, rec::Imu* m) {
    std::vector<double> r;
    if (!imu->Next(&r)) return false;
    *t_s = r[c[0]];
    m->header = At(r[c[0]], "imu_link");
    m->orientation_covariance[0] = -1.0;  // no orientation estimate (REP-145)
    m->angular_velocity = {r[c[1]], r[c[2]], r[c[3]]};
    m->linear_acceleration = {r[c[4]], r[c[5]], r[c[6]]};
    return true;
  });
}

// The sprockets' angles from the encoder counts, and their rates as the backward
// difference of the counts (what the wheel odometry sees).
Stream JointStream(const fs::path& file, int ticks_per_rev) {
  auto enc = std::make_shared<CsvReader>(file);
  enc->Column("left_ticks");
  enc->Column("right_ticks");
  auto previous = std::make_shared<std::vector<double>>();  // the row before, if any
  const double rad_per_tick = 2.0 * M_PI / ticks_per_rev;
  return MakeStream<rec::JointState>(
      "/joint_states", [enc, previous, rad_per_tick](double* t_s, rec::JointState* j) {
        std::vector<double> r;
        if (!enc->Next(&r)) return false;
        *t_s = r[0];
        j->header = At(r[0], "");
        j->name = {"left_sprocket_joint", "right_sprocket_joint"};
        j->position = {r[1] * rad_per_tick, r[2] * rad_per_tick};
        j->velocity = {0.0, 0.0};
        if (!previous->empty()) {
          const std::vector<double>& p = *previous;
          const double dt = r[0] - p[0];
          if (dt > 0)
            j->velocity = {(r[1] - p[1]) * rad_per_tick / dt, (r[2] - p[2]) * rad_per_tick / dt};
        }
        *previous = std::move(r);
        return true;
      });
}

// /scan from scan.csv: the beams fan counter-clockwise from straight ahead over a full
// turn, all taken at the scan's time (the simulated sensor does not spin during a
// scan), +inf where no return (REP-117).
Stream ScanStream(const fs::path& file, const robot::RangeSensorOptions& sensor) {
  auto scans = std::make_shared<CsvReader>(file);
  const std::size_t beams = static_cast<std::size_t>(sensor.beams);
  if (scans->columns().size() != beams + 1) {
    throw std::runtime_error(file.string() + ": " + std::to_string(scans->columns().size() - 1) +
                             " ranges per row, the scenario's range sensor has " +
                             std::to_string(beams) + " beams");
  }
  rec::LaserScan shape;
  shape.angle_increment = static_cast<float>(2.0 * M_PI / sensor.beams);
  shape.angle_max = static_cast<float>(2.0 * M_PI * (sensor.beams - 1) / sensor.beams);
  shape.scan_time = static_cast<float>(1.0 / sensor.rate_hz);
  shape.range_min = static_cast<float>(sensor.min_range_m);
  shape.range_max = static_cast<float>(sensor.max_range_m);
  return MakeStream<rec::LaserScan>("/scan", [scans, shape](double* t_s, rec::LaserScan* m) {
    std::vector<double> r;
    if (!scans->Next(&r)) return false;
    *t_s = r[0];
    *m = shape;
    m->header = At(r[0], "range_sensor");
    m->ranges.assign(r.begin() + 1, r.end());
    return true;
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
  return OnceStream<rec::TFMessage>("/tf_static", m);
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

// camera/times.txt (one time [s] per line), read line by line: the frames' times and
// numbers.
class FrameTimes {
 public:
  explicit FrameTimes(const fs::path& file) : file_(file), in_(file) {}
  /// The next frame's time; false at the end.
  bool Next(double* t_s) {
    std::string line;
    if (!std::getline(in_, line)) return false;
    ++number_;
    char* end = nullptr;
    *t_s = std::strtod(line.c_str(), &end);
    if (line.empty() || *end != '\0') {
      throw std::runtime_error(file_.string() + ":" + std::to_string(number_) + ": not a time: '" +
                               line + "'");
    }
    return true;
  }
  /// The number (from 0) of the frame Next() gave last.
  std::size_t frame() const { return static_cast<std::size_t>(number_ - 1); }

 private:
  fs::path file_;
  std::ifstream in_;
  int number_ = 0;
};

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
                      std::vector<Stream>* streams) {
  const std::string side = c == 0 ? "left" : "right";
  const fs::path times = camera / "times.txt";
  if (!fs::exists(times) || fs::file_size(times) == 0) {
    streams->push_back(OnceStream<rec::CameraInfo>("/stereo/" + side + "/camera_info", info));
    return;
  }
  auto image_times = std::make_shared<FrameTimes>(times);
  streams->push_back(MakeStream<rec::CompressedImage>(
      "/stereo/" + side + "/image_raw/compressed",
      [image_times, info, dir = camera / side](double* t_s, rec::CompressedImage* m) {
        if (!image_times->Next(t_s)) return false;
        char name[16];
        std::snprintf(name, sizeof(name), "%06zu.png", image_times->frame());
        *m = rec::CompressedImage{At(*t_s, info.header.frame_id), "png", ReadBytes(dir / name)};
        return true;
      }));
  auto info_times = std::make_shared<FrameTimes>(times);
  streams->push_back(MakeStream<rec::CameraInfo>(
      "/stereo/" + side + "/camera_info", [info_times, info](double* t_s, rec::CameraInfo* m) {
        if (!info_times->Next(t_s)) return false;
        *m = info;
        m->header.stamp = rec::Time::FromSeconds(*t_s);
        return true;
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
  streams.push_back(ClockStream(dir / "ground_truth.tum"));
  const std::vector<std::string> estimates = EstimateNames(dir);
  if (std::count(estimates.begin(), estimates.end(), "fused"))
    streams.push_back(TfStream(dir / "fused.tum"));
  streams.push_back(OdometryStream("/ground_truth/odom", dir / "ground_truth.tum", "map",
                                   "base_link_ground_truth",
                                   physics ? dir / "ground_truth_twist.csv" : fs::path()));
  for (const std::string& name : estimates) {
    streams.push_back(OdometryStream("/" + name + "/odom", dir / (name + ".tum"), "odom",
                                     name == "fused" ? "base_link" : "base_link_" + name, {}));
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
    const perception::StereoRectifier rectifier(*given.stereo);  // the maps built once
    for (int c = 0; c < 2; ++c) {
      AddCameraStreams(CameraInfoOf(*given.stereo, rectifier, c), c, dir / "camera", &streams);
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
  const fs::path file = dir / "run.mcap";
  rec::McapWriter writer(file.string());
  std::map<std::string, std::uint16_t> schemas;
  for (Stream& s : streams) {
    if (!schemas.count(s.type)) schemas[s.type] = writer.AddSchema(s.type, "ros2msg", s.definition);
    s.channel = writer.AddChannel(schemas[s.type], s.topic, "cdr",
                                  {{"offered_qos_profiles", QosProfile(s.transient_local)}});
  }
  // Every message by time, ties in channel order then row order (each file is in time
  // order): a merge of the streams, each holding its next message.
  struct Head {
    std::uint64_t t_ns;
    std::size_t stream;
    bool operator>(const Head& o) const {
      return t_ns != o.t_ns ? t_ns > o.t_ns : stream > o.stream;
    }
  };
  std::vector<std::vector<std::uint8_t>> next(streams.size());
  std::priority_queue<Head, std::vector<Head>, std::greater<Head>> heads;
  const auto advance = [&](std::size_t s) {
    double t_s = 0.0;
    if (streams[s].next(&t_s, &next[s])) heads.push({rec::Time::FromSeconds(t_s).Nanoseconds(), s});
  };
  for (std::size_t s = 0; s < streams.size(); ++s) advance(s);
  RunBagSummary summary;
  std::uint64_t start = 0, end = 0;
  while (!heads.empty()) {
    const Head h = heads.top();
    heads.pop();
    writer.Write(streams[h.stream].channel, h.t_ns, h.t_ns, next[h.stream]);
    if (summary.messages == 0) start = h.t_ns;
    end = h.t_ns;
    ++summary.messages;
    ++streams[h.stream].count;
    advance(h.stream);
  }
  writer.Close();
  for (const Stream& s : streams) summary.messages_per_topic[s.topic] = s.count;
  std::ofstream yaml(dir / "metadata.yaml");
  yaml << MetadataYaml(streams, summary.messages_per_topic, start, end, summary.messages);
  if (!yaml.flush()) throw std::runtime_error((dir / "metadata.yaml").string() + ": write failed");
  return summary;
}

}  // namespace trackbed::runner
