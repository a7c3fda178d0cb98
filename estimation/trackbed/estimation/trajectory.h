// Trajectories: time-stamped poses of the body frame in the world frame, and
// their TUM text form (`t x y z qx qy qz qw`, t in seconds).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace trackbed::estimation {

struct StampedPose {
  double t_s = 0.0;
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
};

using Trajectory = std::vector<StampedPose>;

/// One TUM line (no newline), with enough digits to round-trip a double.
std::string FormatTumLine(const StampedPose& pose);

/// Length [m] of the polyline through the trajectory's positions (3-D).
double PathLength(const Trajectory& trajectory);

}  // namespace trackbed::estimation
