// Moving occluders: person-sized bodies walking scripted paths, seen by the
// cameras (and, later, the range sensor). Their motion is kinematic: a
// function of simulation time only.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace trackbed::sim {

struct OccluderSpec {
  /// Walking path in the world xy plane [m], at least one point (one point: standing still).
  std::vector<Eigen::Vector2d> waypoints;
  /// Walking speed [m/s], > 0.
  double speed_mps = 1.2;
  /// Time the walk starts [s]; before it the body stands at the first waypoint.
  double start_s = 0.0;
  /// After the last waypoint: walk the path back (true) or stand still (false).
  bool back_and_forth = true;
  /// Height [m] and body radius [m] of the person.
  double height_m = 1.75;
  double radius_m = 0.25;
  std::string appearance = "person";

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("waypoints", &waypoints);
    a->Visit("speed_mps", &speed_mps);
    a->Visit("start_s", &start_s);
    a->Visit("back_and_forth", &back_and_forth);
    a->Visit("height_m", &height_m);
    a->Visit("radius_m", &radius_m);
    a->Visit("appearance", &appearance);
  }
};

/// Where an occluder is at time `t_s`: xy position [m] and heading [rad].
struct OccluderPose {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;
};

OccluderPose OccluderPoseAt(const OccluderSpec& spec, double t_s);

}  // namespace trackbed::sim
