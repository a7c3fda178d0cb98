// The motion of what carries the sensors and the state of its two tracks: what the
// closed loop reads from a robot::Platform (robot/platform.h) at every step.
#pragma once

#include <Eigen/Geometry>

namespace trackbed::robot {

/// Index of the two tracks.
enum Side { kLeft = 0, kRight = 1 };

/// Kinematic state of the chassis (body frame: x forward, y left, z up, origin
/// at the centre of mass).
struct ChassisState {
  Eigen::Isometry3d T_world_body = Eigen::Isometry3d::Identity();
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();      ///< Linear velocity [m/s].
  Eigen::Vector3d omega_world = Eigen::Vector3d::Zero();  ///< Angular velocity [rad/s].
};

/// What one track is doing now.
struct TrackState {
  double sprocket_angle_rad = 0.0;
  double sprocket_speed_radps = 0.0;
  double motor_torque_nm = 0.0;
  double track_speed_mps = 0.0;    ///< r ω.
  double ground_speed_mps = 0.0;   ///< Chassis velocity at the track centreline, along body x.
  double slip_velocity_mps = 0.0;  ///< ground − track speed (Ham et al. sign).
  double normal_load_n = 0.0;      ///< Sum over stations.
  double traction_n = 0.0;         ///< Longitudinal shear force on the vehicle.
  double compaction_resistance_n = 0.0;  ///< Sum of the stations' rut-making resistance.
  /// Sum of the stations' bulldozing resistance to a sideways skid (its capacity,
  /// mobilised with the lateral shear).
  double bulldozing_resistance_n = 0.0;
  double running_gear_resistance_n = 0.0;  ///< Internal resistance at the track.
  int stations_in_contact = 0;
  /// How long the motor has held its torque limit with the sprocket below a tenth
  /// of its command [s] (0 while it is not).
  double stall_time_s = 0.0;
};

}  // namespace trackbed::robot
