// URDF robots read through urdfdom and mapped onto trackbed's vehicle and stereo mount
// (docs/gazebo_users.md, "A robot in URDF"): the chassis's box, the total mass, the
// wheels' or road wheels' layout (gauge, stations, sprocket radius), the heights above
// the ground, and the camera's mount from its joint. What has no key is listed.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "trackbed/description/description_error.h"
#include "trackbed/description/sensor_blocks.h"

namespace trackbed::description {

/// A URDF robot a scenario names (`robot.description`).
struct UrdfRobotOptions {
  /// The URDF file, relative to the scenario's folder; absolute once the scenario is
  /// loaded. Plain URDF: a `.urdf.xacro` is expanded first (`xacro robot.urdf.xacro >
  /// robot.urdf`).
  std::string file;
  /// The link whose origin is the stereo camera's (the midpoint between its optical
  /// centres, x along the view); empty: the one link whose name holds "camera" and not
  /// "optical".
  std::string camera_link;
  /// Set when the robot has been mapped into the robot's keys (a run folder's
  /// scenario.yaml holds the mapped values, which are not mapped again).
  bool mapped = false;
  /// What the robot holds that has no key, one entry each (filled when mapped).
  std::vector<std::string> unmapped;

  /// Throws OptionError naming the field: `file` empty.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("file", &file);
    a->Visit("camera_link", &camera_link);
    a->Visit("mapped", &mapped);
    a->Visit("unmapped", &unmapped);
  }
};

/// What a URDF robot maps onto (robot.vehicle and robot.stereo's keys); each value is
/// rounded to 1e-9 of its unit, so that a file's decimals give the decimals a scenario
/// would rather than their binary sums' last bits.
struct UrdfRobot {
  double mass_kg = 0.0;             ///< Every link's inertial mass summed [kg].
  Eigen::Vector3d hull_size_m;      ///< The chassis's box: length, width, height [m].
  double com_height_m = 0.0;        ///< Centre of mass above flat ground at rest [m].
  double ground_clearance_m = 0.0;  ///< The box's underside above flat ground [m].
  double track_gauge_m = 0.0;       ///< Between the sides' wheel centrelines [m].
  double track_width_m = 0.0;       ///< A wheel's (a road wheel's) width [m].
  double sprocket_radius_m = 0.0;   ///< The driven wheel's (the sprocket's) radius [m].
  std::vector<double> station_x_m;  ///< Wheel centres along x from the centre of mass [m].
  bool tracks = false;              ///< A sprocket link was found: a tracked robot.
  /// Tracks: from the rear road wheel's rim to the front one's (their centres' span
  /// plus a diameter) [m].
  std::optional<double> track_contact_length_m;
  /// The camera's mount from the centre of mass [m] and its downward pitch [deg].
  std::optional<Eigen::Vector3d> camera_mount_m;
  std::optional<double> camera_pitch_down_deg;
  /// The `<gazebo reference="LINK">` blocks' first camera (or multicamera) and first
  /// ray or lidar sensor; the camera's mount and pitch replace the camera link's.
  SensorBlocks sensors;
  /// What has no key, one entry each: what it is, where, and why.
  std::vector<std::string> unmapped;
};

/// Reads `options.file` through urdfdom and maps it. Throws DescriptionError naming the
/// file and the element: urdfdom's own errors (captured, not printed), no chassis box,
/// wheels not in left–right pairs, no camera link when asked for one.
UrdfRobot ReadUrdfRobot(const UrdfRobotOptions& options);

/// As ReadUrdfRobot, from URDF text; `source_name` names it in errors.
UrdfRobot ReadUrdfRobotString(const std::string& urdf_text, const std::string& source_name,
                              const UrdfRobotOptions& options);

}  // namespace trackbed::description
