// Gazebo sensor blocks (`<sensor type="camera">`, `multicamera`, `ray`, `gpu_ray`,
// `lidar`, `gpu_lidar`) mapped onto robot.stereo's and robot.range_sensor's keys
// (docs/gazebo_users.md, "Sensors"). What has no key is listed.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

namespace trackbed::description {

/// A camera or multicamera block as robot.stereo's keys.
struct CameraSensorMapping {
  std::string name;                  ///< The sensor's name.
  int width_px = 0, height_px = 0;   ///< `<image><width>`, `<height>`.
  double hfov_deg = 0.0;             ///< `<horizontal_fov>`: the focal length's source.
  std::optional<double> rate_hz;     ///< `<update_rate>`, when > 0.
  double near_m = 0.0, far_m = 0.0;  ///< `<clip><near>`, `<far>`.
  std::optional<double> noise_std;   ///< Gaussian `<stddev>` × 255 [grey levels].
  std::optional<double> baseline_m;  ///< A multicamera's: between its first two cameras.
  Eigen::Vector3d mount_m = Eigen::Vector3d::Zero();  ///< From the centre of mass [m].
  double pitch_down_deg = 0.0;                        ///< The view's downward pitch.
};

/// A ray or lidar block as robot.range_sensor's keys.
struct RangeSensorMapping {
  std::string name;                             ///< The sensor's name.
  int beams = 0;                                ///< Over 360° at the block's angular spacing.
  std::optional<double> rate_hz;                ///< `<update_rate>`, when > 0.
  double min_range_m = 0.0, max_range_m = 0.0;  ///< `<range><min>`, `<max>`.
  std::optional<double> noise_std_m;            ///< Gaussian `<stddev>` [m].
  Eigen::Vector3d mount_m = Eigen::Vector3d::Zero();  ///< From the centre of mass [m].
};

/// The first camera block and the first range block a description holds.
struct SensorBlocks {
  std::optional<CameraSensorMapping> camera;
  std::optional<RangeSensorMapping> range;
};

}  // namespace trackbed::description
