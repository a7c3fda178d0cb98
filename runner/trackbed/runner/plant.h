// The plant of one run: the simulated world and the robot as built in it (its body, its
// sensors), built from the scenario; what the closed loop steps and samples.
#pragma once

#include <memory>

#include "trackbed/robot/encoder.h"
#include "trackbed/robot/imu.h"
#include "trackbed/robot/platform.h"
#include "trackbed/robot/pose_path_carrier.h"
#include "trackbed/robot/range_sensor.h"
#include "trackbed/robot/stereo_camera.h"
#include "trackbed/runner/robot_build.h"
#include "trackbed/scenario/scenario.h"
#include "trackbed/sim/track_marks.h"
#include "trackbed/sim/world.h"

namespace trackbed::runner {

/// The world and the robot in it. Members are destroyed in reverse order, each before
/// what it refers to (the world last). Not copyable.
struct Plant {
  std::unique_ptr<sim::World> world;
  /// The robot's track marks, with `scene.appearance.track_marks` (shared with a later
  /// pass that continues them); null without.
  std::shared_ptr<sim::TrackMarks> track_marks;
  /// The tracked vehicle in the physics, or the carrier of a pose path.
  std::unique_ptr<robot::Platform> vehicle;
  const robot::PosePathCarrier* carrier = nullptr;  ///< `vehicle`, when it is one
  std::unique_ptr<robot::SprocketEncoders> encoders;
  std::unique_ptr<robot::Imu> imu;
  std::unique_ptr<robot::StereoCamera> camera;       ///< null unless robot.stereo.enabled
  std::unique_ptr<robot::RangeSensor> range_sensor;  ///< null unless robot.range_sensor.enabled
};

/// `scenario`'s world and its robot as built `robot.truth`, carried along the drive's
/// curve when `pose_path` (Scenario::CarriedOnPosePath), else a tracked vehicle in the
/// physics. Each part draws from its own stream of the scenario's seed
/// (split_mix::Stream: 0 terrain, 1 IMU, 2 the rendered scene, 3 the camera's noise,
/// 4 range sensor, 6 the image sensors' pattern; 5 draws the robot as built).
/// With `scene.appearance.track_marks` on a tracked vehicle, its ruts are recorded into
/// `track_marks` (a new record when null) and drawn by the camera.
Plant BuildPlant(const scenario::Scenario& scenario, const RobotBuild& robot, bool pose_path,
                 std::shared_ptr<sim::TrackMarks> track_marks = nullptr);

}  // namespace trackbed::runner
