// The planar range sensor (see range_sensor.h).
#include "trackbed/robot/range_sensor.h"

#include <cmath>
#include <limits>

#include "trackbed/common/option_error.h"
#include "trackbed/common/random.h"
#include "trackbed/common/split_mix.h"

namespace trackbed::robot {

void RangeSensorOptions::Validate() const {
  if (beams < 8) throw OptionError("beams", "must be >= 8 (got " + std::to_string(beams) + ")");
  option_check::Positive("rate_hz", rate_hz);
  option_check::Positive("min_range_m", min_range_m);
  option_check::Positive("max_range_m", max_range_m);
  if (!(max_range_m > min_range_m)) {
    throw OptionError("max_range_m", "must be > min_range_m");
  }
  option_check::NonNegative("noise_std_m", noise_std_m);
  if (!mount_m.allFinite()) throw OptionError("mount_m", "must be finite");
}

RangeSensor::RangeSensor(const RangeSensorOptions& options, std::uint64_t seed)
    : options_(options), seed_(seed) {
  options_.Validate();
  angles_rad_.resize(static_cast<std::size_t>(options_.beams));
  for (int k = 0; k < options_.beams; ++k) {
    angles_rad_[static_cast<std::size_t>(k)] = 2.0 * M_PI * k / options_.beams;
  }
}

Eigen::Isometry3d RangeSensor::T_body_sensor() const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = options_.mount_m;
  return T;
}

RangeScanSample RangeSensor::Scan(const sim::World& world, const Eigen::Isometry3d& T_world_body,
                                  double t_s, std::uint64_t index) const {
  RangeScanSample scan;
  scan.t_s = t_s;
  scan.max_range_m = options_.max_range_m;
  scan.angles_rad = angles_rad_;
  scan.T_world_sensor = T_world_body * T_body_sensor();
  scan.ranges_m.resize(angles_rad_.size());
  const Eigen::Vector3d origin = scan.T_world_sensor.translation();
  const Eigen::Matrix3d& R = scan.T_world_sensor.linear();
  std::uint64_t state = split_mix::Mix(seed_ ^ split_mix::Mix(index));
  for (std::size_t k = 0; k < angles_rad_.size(); ++k) {
    // Box–Muller from two draws of the scan's own stream (same bits on every platform).
    state = split_mix::Mix(state);
    const double u1 = random::OpenUnitInterval(state);
    state = split_mix::Mix(state);
    const double u2 = random::OpenUnitInterval(state);
    const double noise = options_.noise_std_m * random::BoxMuller(u1, u2);
    const Eigen::Vector3d direction =
        R * Eigen::Vector3d(std::cos(angles_rad_[k]), std::sin(angles_rad_[k]), 0.0);
    const std::optional<sim::RayHit> hit =
        world.CastRay(origin, origin + options_.max_range_m * direction, sim::kGroupObstacle);
    double range = std::numeric_limits<double>::infinity();
    if (hit) {
      const double r = hit->fraction * options_.max_range_m + noise;
      if (r >= options_.min_range_m && r < options_.max_range_m) range = r;
    }
    scan.ranges_m[k] = range;
  }
  return scan;
}

}  // namespace trackbed::robot
