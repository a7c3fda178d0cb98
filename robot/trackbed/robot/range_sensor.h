// A planar 2-D range sensor (a spinning lidar) on the robot: beams fanned over a
// full turn in the sensor's own plane, cast against the scene's obstacles with
// Bullet ray tests. It sees objects only: the terrain's returns are assumed filtered
// out, as a 2-D lidar's ground hits are on a real robot. Noise is seeded.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/sim/world.h"

namespace trackbed::robot {

struct RangeSensorOptions {
  /// Whether the robot carries the sensor (closed-loop navigation turns it on).
  bool enabled = false;
  /// Beams per scan, evenly spaced over 360° starting straight ahead, counter-clockwise,
  /// >= 8.
  int beams = 360;
  /// Scan rate [Hz], > 0.
  double rate_hz = 10.0;
  /// Range limits [m], 0 < min < max.
  double min_range_m = 0.1;
  double max_range_m = 8.0;
  /// Standard deviation of the additive range noise [m], >= 0.
  double noise_std_m = 0.01;
  /// Sensor origin in the body frame [m] (x forward, y left, z up from the centre of
  /// mass, which is 0.20 m above flat ground).
  Eigen::Vector3d mount_m{0.2, 0.0, 0.15};

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("enabled", &enabled);
    a->Visit("beams", &beams);
    a->Visit("rate_hz", &rate_hz);
    a->Visit("min_range_m", &min_range_m);
    a->Visit("max_range_m", &max_range_m);
    a->Visit("noise_std_m", &noise_std_m);
    a->Visit("mount_m", &mount_m);
  }
};

/// One scan: ranges in beam order (+infinity: no return within max_range_m), the beam
/// angles in the sensor frame and the sensor's true pose when it was taken.
struct RangeScanSample {
  double t_s = 0.0;
  std::vector<double> ranges_m;
  std::vector<double> angles_rad;
  double max_range_m = 0.0;
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
};

/// Casts scans; the noise of scan k depends only on (seed, k). Not copyable.
class RangeSensor {
 public:
  RangeSensor(const RangeSensorOptions& options, std::uint64_t seed);
  RangeSensor(const RangeSensor&) = delete;
  RangeSensor& operator=(const RangeSensor&) = delete;

  const RangeSensorOptions& options() const { return options_; }
  /// The sensor frame in the body frame (axes parallel to the body's).
  Eigen::Isometry3d T_body_sensor() const;
  /// Scan number `index` taken at `t_s` with the body at `T_world_body`.
  RangeScanSample Scan(const sim::World& world, const Eigen::Isometry3d& T_world_body, double t_s,
                       std::uint64_t index) const;

 private:
  RangeSensorOptions options_;
  std::uint64_t seed_;
  std::vector<double> angles_rad_;
};

}  // namespace trackbed::robot
