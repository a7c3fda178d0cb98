// What carries the robot's sensors through the world, as the closed loop sees it: the
// tracked vehicle of the physics (robot/tracked_vehicle.h) or a body moved along a
// scripted path without physics (robot/pose_path_carrier.h). Both report the chassis's
// true motion and each track's state (its sprocket turns what the encoders count).
#pragma once

#include "trackbed/robot/track_state.h"

namespace trackbed::robot {

/// The interface of a sensor carrier. Not copyable.
class Platform {
 public:
  Platform() = default;
  Platform(const Platform&) = delete;
  Platform& operator=(const Platform&) = delete;
  virtual ~Platform() = default;

  /// Commands the track surface speeds [m/s]; a carrier that follows a scripted path
  /// ignores them.
  virtual void CommandTrackSpeeds(double left_mps, double right_mps) = 0;
  /// Advances the carrier by one step of dt_s [s]: for the tracked vehicle, its ground
  /// forces (the World's step then moves it); for a kinematic carrier, the motion itself.
  virtual void ApplyForces(double dt_s) = 0;
  /// Whether the World must be stepped after ApplyForces to move the carrier.
  virtual bool needs_physics() const = 0;
  /// The chassis's true pose and velocities.
  virtual ChassisState chassis() const = 0;
  /// One track's state (sprocket angle and speed, slip, loads).
  virtual const TrackState& track(Side side) const = 0;
  /// True when the carrier can no longer move as commanded (a stalled motor).
  virtual bool stalled() const = 0;
};

}  // namespace trackbed::robot
