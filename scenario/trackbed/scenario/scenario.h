// A scenario: everything one closed-loop run needs, as plain values.
//
// The YAML file format mirrors these structs key for key: each struct's Serialize
// (here, and beside the sim/robot/estimation/navigation/teach_repeat options structs
// it holds) lists its keys for the config archive (trackbed/common/archive.h), which
// reads and writes them (scenario_yaml.h). docs/scenario_format.md lists every key with
// its unit and default.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "trackbed/common/archive.h"
#include "trackbed/common/archive_eigen.h"
#include "trackbed/description/sdf_world.h"
#include "trackbed/description/urdf_robot.h"
#include "trackbed/estimation/localization.h"
#include "trackbed/navigation/kinematic_simulation.h"
#include "trackbed/navigation/navigator_factory.h"
#include "trackbed/navigation/pure_pursuit.h"
#include "trackbed/navigation/scan_clustering.h"
#include "trackbed/render/renderer.h"
#include "trackbed/robot/as_built.h"
#include "trackbed/robot/encoder.h"
#include "trackbed/robot/imu.h"
#include "trackbed/robot/imu_parts.h"
#include "trackbed/robot/range_sensor.h"
#include "trackbed/robot/stereo_rig.h"
#include "trackbed/robot/tracked_vehicle.h"
#include "trackbed/sim/corridor_fittings.h"
#include "trackbed/sim/geodetic_origin.h"
#include "trackbed/sim/object_scatter.h"
#include "trackbed/sim/occluder.h"
#include "trackbed/sim/static_object.h"
#include "trackbed/sim/terrain.h"
#include "trackbed/sim/world.h"
#include "trackbed/teach_repeat/funnel_lane_controller.h"
#include "trackbed/teach_repeat/milestone_builder.h"
#include "trackbed/teach_repeat/milestone_localizer_3d.h"
#include "trackbed/teach_repeat/teach_map.h"
#include "trackbed/teach_repeat/teach_repeat_metrics.h"

namespace trackbed::archive {

/// Scene objects (`scene.objects`) have a file form of their own rather than a field
/// list: `type` picks the shape and the default appearance, a wall may be given by
/// `from`/`to`, a box's yaw is in degrees (scenario_yaml.cpp).
template <>
struct Codec<sim::StaticObject> {
  static void Read(const Node& node, const std::string& path, Wording wording,
                   sim::StaticObject* object);
  static Node Write(const sim::StaticObject& object);
};

}  // namespace trackbed::archive

namespace trackbed::scenario {

/// The world the robot drives in.
struct SceneSpec {
  /// Free-form name (corridor, outdoor, …).
  std::string name = "unnamed";
  sim::WorldOptions world;
  sim::TerrainOptions terrain;
  std::vector<sim::StaticObject> objects;
  /// Objects scattered by density from the seed (sim/object_scatter.h), added to
  /// `objects`; the drive's route and the start are kept clear of them.
  std::vector<sim::ObjectScatter> scatter;
  /// Corridor fittings (sim/corridor_fittings.h) on the walls facing the drive's
  /// route, added to `objects` from the seed; absent: none.
  std::optional<sim::CorridorFittings> fittings;
  /// Light and visual dressing for the cameras.
  render::SceneAppearance appearance;
  /// People walking scripted paths (seen by the cameras).
  std::vector<sim::OccluderSpec> occluders;
  /// An SDF world mapped into this scene when the scenario is loaded
  /// (docs/gazebo_users.md): its objects join `objects`, its physics, gravity, sun
  /// and ground friction set `world`, `appearance` and `terrain.default_material`.
  std::optional<description::SdfWorldOptions> sdf;
  /// Where on the Earth the world's origin lies (sim/geodetic_origin.h): the IMU's gyro
  /// senses the Earth's rotation, and its normal gravity is `world.gravity_mps2` where
  /// that key is not given. Absent: a world that does not turn, gravity as given.
  std::optional<sim::GeodeticOrigin> geodetic_origin;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("name", &name);
    a->Visit("world", &world);
    a->Visit("terrain", &terrain);
    a->Visit("objects", &objects);  // a file form of their own: Codec<sim::StaticObject> above
    a->Visit("scatter", &scatter);
    a->Visit("fittings", &fittings, archive::kOmitEmpty);
    a->Visit("appearance", &appearance);
    a->Visit("occluders", &occluders);
    a->Visit("sdf", &sdf, archive::kOmitEmpty);
    a->Visit("geodetic_origin", &geodetic_origin, archive::kOmitEmpty);
  }
};

/// Where the robot starts (on the ground, aligned with its slope).
struct StartPose {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_deg = 0.0;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("x_m", &x_m);
    a->Visit("y_m", &y_m);
    a->Visit("yaw_deg", &yaw_deg);
  }
};

struct RobotSpec {
  StartPose start;
  robot::TrackedVehicleOptions vehicle;
  robot::EncoderOptions encoders;
  robot::ImuOptions imu;
  robot::StereoRigOptions stereo;
  robot::RangeSensorOptions range_sensor;
  /// How far the robot as built departs from its design and how well its software
  /// knows it (docs/calibration.md): ideal (the design, the truth given), typical or
  /// harsh; `imperfections` overrides the profile key by key.
  robot::Realism realism = robot::Realism::kTypical;
  robot::Imperfections imperfections;
  /// Seed of the robot as built and of its calibration's errors; none: derived from
  /// the run's seed.
  std::optional<std::uint64_t> as_built_seed;
  /// A URDF robot mapped into `vehicle` and `stereo`'s mount when the scenario is
  /// loaded (docs/gazebo_users.md): the keys it gives replace the scenario's.
  std::optional<description::UrdfRobotOptions> description;
  /// A folder of calibration files (stereo_calibration.json, imu_calibration.json,
  /// vehicle_calibration.json) given to the software instead of the profile's,
  /// relative to the scenario file; empty: none.
  std::string calibration_dir;

  void Validate() const;
  /// The seed of the robot as built: as_built_seed, else one derived from `run_seed`.
  std::uint64_t AsBuiltSeed(std::uint64_t run_seed) const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("start", &start);
    a->Visit("vehicle", &vehicle);
    a->Visit("encoders", &encoders);
    a->Visit("imu", &imu);
    a->Visit("stereo", &stereo);
    a->Visit("range_sensor", &range_sensor);
    a->VisitEnum("realism", &realism,
                 {{"ideal", robot::Realism::kIdeal},
                  {"typical", robot::Realism::kTypical},
                  {"harsh", robot::Realism::kHarsh}});
    a->Visit("imperfections", &imperfections);
    a->Visit("as_built_seed", &as_built_seed, archive::kOmitEmpty);
    a->Visit("calibration_dir", &calibration_dir, archive::kOmitEmpty);
    a->Visit("description", &description, archive::kOmitEmpty);
  }
};

/// One command of a time-stamped script, held until the next one.
/// Either a body twist (v, yaw rate; converted with the nominal gauge) or track speeds.
struct DriveCommand {
  double t_s = 0.0;
  bool track_speeds = false;
  double v_mps = 0.0;
  double yaw_rate_radps = 0.0;
  double left_mps = 0.0;
  double right_mps = 0.0;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("t_s", &t_s);
    // A twist or track speeds, never both; reading sets track_speeds from the keys used.
    if (a->Either(&track_speeds, {"v_mps", "yaw_rate_radps"}, {"left_mps", "right_mps"})) {
      a->Visit("left_mps", &left_mps);
      a->Visit("right_mps", &right_mps);
    } else {
      a->Visit("v_mps", &v_mps);
      a->Visit("yaw_rate_radps", &yaw_rate_radps);
    }
  }
};

/// How the robot is commanded: a replayed script, or a pure-pursuit driver
/// following a reference path on ground truth (the paper's human driver).
/// The fastest a pose path may carry the sensors [m/s]: a car at 360 km/h.
inline constexpr double kMaxPosePathSpeedMps = 100.0;

struct DriveSpec {
  /// kPath: pure pursuit of `waypoints` on ground truth; kScript: `script` replayed;
  /// kPosePath: no driving — the body is carried along a smooth curve through
  /// `waypoints` at `pursuit.speed_mps`, without physics (robot/pose_path_carrier.h).
  enum class Mode { kScript, kPath, kPosePath };
  Mode mode = Mode::kPath;
  std::vector<DriveCommand> script;
  /// Reference path vertices [m], world frame.
  std::vector<Eigen::Vector2d> waypoints;
  /// Whether the path closes back on its first vertex.
  bool closed = false;
  /// Laps of a closed path to drive, >= 1.
  int laps = 1;
  /// The path's follower (navigation/pure_pursuit.h), its keys in this same map:
  /// `speed_mps` (pose_path: the carrier's speed over the ground, at most
  /// kMaxPosePathSpeedMps), `lookahead_m`, `goal_tolerance_m`, `max_yaw_rate_radps`,
  /// `turn_in_place_rad`.
  navigation::PurePursuitOptions pursuit;
  /// Rate of the driver [Hz], > 0.
  double rate_hz = 20.0;
  /// How long the robot stands still before the drive starts [s], >= 0: the tracks are
  /// commanded to zero, so the stack can take the gyro's bias from the standstill
  /// (estimation.gyro.zero_velocity_bias); a script's times and the path count from its
  /// end, and the run's duration is `duration_s` plus it (Scenario::RunDuration).
  /// Closed-loop navigation starts after it too. Not with a pose path, which is carried
  /// without a drive.
  double start_standstill_s = 0.0;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->VisitEnum(
        "mode", &mode,
        {{"path", Mode::kPath}, {"script", Mode::kScript}, {"pose_path", Mode::kPosePath}});
    a->Visit("waypoints", &waypoints);
    a->Visit("closed", &closed);
    a->Visit("laps", &laps);
    pursuit.Serialize(a);
    a->Visit("rate_hz", &rate_hz);
    a->Visit("script", &script);
    a->Visit("start_standstill_s", &start_standstill_s);
  }
};

/// The localization stack run on the robot's sensors (Ham et al. 2012).
struct EstimationSpec {
  /// Run the estimators (wheel odometry always; VO and fusion when the stereo camera is on).
  bool enabled = true;
  /// ICR expansion factor χ for the effective gauge B_eff = χ·B, in [0.2, 5], where the
  /// robot's given calibration has none (calibration_dir's vehicle_calibration.json
  /// gives its own). Default: the value the calibration run
  /// scenes/calibration/icr_turns.yaml fits on the hard floor (1.239).
  double icr_expansion = 1.239;
  /// The localization stack's options (estimation/localization.h), their keys in this
  /// same map: `estimation.wheel.*`, `estimation.vo.*`, `estimation.fusion.*`,
  /// `estimation.min_inliers_for_slip`, `estimation.vo_coast_time_s`, `estimation.ekf.*`.
  /// Defaults: the tracked robot's (LocalizationOptions::TrackedRobot()). The fields the
  /// robot's given calibration decides (its wheels' geometry, the IMU's calibration) are
  /// set by the runner (runner/trackbed/runner/localization_options.h).
  estimation::LocalizationOptions localization = estimation::LocalizationOptions::TrackedRobot();

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("enabled", &enabled);
    a->Visit("icr_expansion", &icr_expansion);
    localization.Serialize(a);
  }
};

/// A circular obstacle of a navigation scene: centre [m] (world frame) and physical
/// radius [m] (0: the paper's point obstacle).
struct NavigationObstacleSpec {
  Eigen::Vector2d center{0.0, 0.0};
  double radius_m = 0.0;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("center", &center);
    a->Visit("radius_m", &radius_m);
  }
};

/// A wall of a navigation scene, seen by the avoider as a chain of circles of radius
/// `radius_m` no farther apart than the safety radius d_max (Jung & Kim 2014).
struct NavigationWallSpec {
  Eigen::Vector2d from{0.0, 0.0};
  Eigen::Vector2d to{0.0, 0.0};
  double radius_m = 0.1;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("from", &from);
    a->Visit("to", &to);
    a->Visit("radius_m", &radius_m);
  }
};

/// Point-to-point navigation (Jung & Kim 2014; docs/navigation.md). With `enabled`, the
/// robot drives from `robot.start` to `goal` under `method` instead of following `drive`.
struct NavigationSpec {
  /// kinematic: the paper's differential-drive simulation (no physics, no camera; the
  /// navigator sees the true pose and the exact circles). closed_loop: the tracked
  /// vehicle in the scene, the navigator seeing `pose_source` and the obstacle circles
  /// clustered from the range sensor's scans (robot.range_sensor).
  enum class Mode { kKinematic, kClosedLoop };
  /// A generated scene (navigation/obstacle_fields.h): none, or a seeded random field
  /// (`field_seed`), the paper's two scenes, or one of the traps.
  enum class Field {
    kNone,
    kRandom,
    kPaperLeft,
    kPaperRight,
    kUTrap,
    kNarrowGap,
    kGoalBesideWall,
    kNarrowCorridor
  };
  /// closed_loop: the pose the navigator sees.
  enum class PoseSource { kFused, kWheelOdometry, kGroundTruth };

  bool enabled = false;
  navigation::NavigationMethod method = navigation::NavigationMethod::kGaussNewtonSubgoal;
  Mode mode = Mode::kKinematic;
  /// Goal pose (x_m, y_m, yaw_deg).
  StartPose goal;
  std::vector<NavigationObstacleSpec> obstacles;
  std::vector<NavigationWallSpec> walls;
  /// A generated scene sets the start, the goal and its obstacles; `obstacles` and
  /// `walls` add to it.
  Field field = Field::kNone;
  /// Seed of the random field (0–99 in docs/navigation.md's study).
  std::uint64_t field_seed = 0;
  /// Safety radius d_max [m], > 0 (the paper's 1 m): the sub-goal method's
  /// (SubgoalOptions::safety_radius_m), the walls' circle spacing and, in closed loop, an
  /// upper bound of the scan clustering's (clustering.wall_spacing_m).
  double safety_radius_m = 1.0;
  /// The robot's footprint radius [m], >= 0: the kinematic simulation's disk for
  /// collisions and clearance, and the footprint every method keeps clear (each
  /// method's robot_radius_m; in closed loop at least the hull's half diagonal).
  double footprint_radius_m = 0.35;
  /// The navigators' options (navigation/navigator_factory.h): the control period, the
  /// kinematic robot (closed loop: replaced by the tracked robot, runner/
  /// navigation_scenario.h), the stop tolerances and the stall time at this level, each
  /// method's gains in its own section (`gauss_newton`, `subgoal`, `potential_field`,
  /// `dwa`).
  navigation::NavigatorOptions navigator;
  /// closed_loop: the pose the navigator sees: fused (needs the stereo camera),
  /// wheel_odometry, or ground_truth.
  PoseSource pose_source = PoseSource::kFused;
  /// closed_loop: top speed of the tracked robot under navigation [m/s], > 0 (the
  /// navigator's wheel-speed limit is this over the sprocket radius).
  double max_speed_mps = 0.4;
  /// closed_loop: yaw-rate limit [rad/s], > 0; a faster command is scaled down with its
  /// forward speed (same curvature). Turning in place at full track speed (1.4 rad/s)
  /// sweeps 8° between camera frames, more than visual odometry tracks reliably.
  double max_yaw_rate_radps = 0.5;
  /// kinematic: the simulation's own knobs (collision substeps, stop on collision).
  navigation::KinematicSimulationOptions kinematic;
  /// closed_loop: range scans into obstacle circles (navigation/scan_clustering.h).
  navigation::ScanClusteringOptions clustering;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    using navigation::NavigationMethod;
    a->Visit("enabled", &enabled);
    a->VisitEnum("method", &method,
                 {{navigation::ToString(NavigationMethod::kGaussNewtonSubgoal),
                   NavigationMethod::kGaussNewtonSubgoal},
                  {navigation::ToString(NavigationMethod::kPotentialField),
                   NavigationMethod::kPotentialField},
                  {navigation::ToString(NavigationMethod::kDwa), NavigationMethod::kDwa}});
    a->VisitEnum("mode", &mode,
                 {{"kinematic", Mode::kKinematic}, {"closed_loop", Mode::kClosedLoop}});
    a->Visit("goal", &goal);
    a->Visit("obstacles", &obstacles);
    a->Visit("walls", &walls);
    a->VisitEnum("field", &field,
                 {{ToString(Field::kNone), Field::kNone},
                  {ToString(Field::kRandom), Field::kRandom},
                  {ToString(Field::kPaperLeft), Field::kPaperLeft},
                  {ToString(Field::kPaperRight), Field::kPaperRight},
                  {ToString(Field::kUTrap), Field::kUTrap},
                  {ToString(Field::kNarrowGap), Field::kNarrowGap},
                  {ToString(Field::kGoalBesideWall), Field::kGoalBesideWall},
                  {ToString(Field::kNarrowCorridor), Field::kNarrowCorridor}});
    a->Visit("field_seed", &field_seed);
    a->Visit("safety_radius_m", &safety_radius_m);
    a->Visit("footprint_radius_m", &footprint_radius_m);
    navigator.Serialize(a);  // its common keys at this level, the methods' sections
    a->VisitEnum("pose_source", &pose_source,
                 {{ToString(PoseSource::kFused), PoseSource::kFused},
                  {ToString(PoseSource::kWheelOdometry), PoseSource::kWheelOdometry},
                  {ToString(PoseSource::kGroundTruth), PoseSource::kGroundTruth}});
    a->Visit("max_speed_mps", &max_speed_mps);
    a->Visit("max_yaw_rate_radps", &max_yaw_rate_radps);
    a->Visit("kinematic", &kinematic);
    a->Visit("clustering", &clustering);
  }

  /// The names of `navigation.field` and `navigation.pose_source` in scenario files.
  static const char* ToString(Field field);
  static const char* ToString(PoseSource source);
};

/// Visual teach & repeat (Choi & Ha 2011; docs/teach_repeat.md). With `enabled`, one run
/// teaches (drives `drive`'s path, the "manual" drive, recording left images into a
/// teach map) and then repeats the route from the images alone.
struct TeachRepeatSpec {
  bool enabled = false;
  /// 2d (Chen & Birchfield 2006, funnel lane) or 3d (Diosi et al. 2007): how the teach
  /// pass cuts milestones (milestones.mode) and which repeater follows them.
  teach_repeat::TeachMode method = teach_repeat::TeachMode::k2d;
  /// A teach map folder (a run folder's teach_map/) to repeat instead of teaching,
  /// relative to the scenario file; empty: teach first.
  std::string map;
  /// Repeat: constant forward speed [m/s] and turn rate [deg/s], > 0 (paper's lab:
  /// 0.05 m/s, 4°/s); either repeater's (forward_speed_mps, and turn_rate_radps or
  /// max_yaw_rate_radps).
  double repeat_speed_mps = 0.05;
  double repeat_turn_rate_deg_s = 4.0;
  /// The repeat starts at robot.start moved by this offset (in the start's frame) …
  StartPose start_offset;
  /// … and by a seeded perturbation of up to 5 cm and 2° (false: none).
  bool start_perturbation = true;
  /// People crossing the view in the repeat only (the teach pass does not see them):
  /// each is one place of Choi & Ha's experiment 1, where features lost and recovered
  /// are counted from its start_s until `recovery_window_s` after its walk ends.
  /// Same keys as scene.occluders; back_and_forth must be false (a walk that ends).
  std::vector<sim::OccluderSpec> occluders;
  /// How long after a crossing's walk ends its place still counts recoveries [s], >= 0.
  double recovery_window_s = 3.0;
  /// The robot stands still through each crossing's window, as in the paper's
  /// experiment 1 (its vision runs on); false: it drives on while people cross.
  bool stop_for_crossings = true;
  /// The teach pass's milestones (teach_repeat/milestone_builder.h).
  teach_repeat::MilestoneBuilderOptions milestones;
  /// The 2D repeater (teach_repeat/funnel_lane_controller.h); its max_milestone_overrun
  /// is the key `max_milestone_overrun` at this level.
  teach_repeat::FunnelLaneOptions funnel_lane;
  /// The 3D repeater (teach_repeat/milestone_localizer_3d.h).
  teach_repeat::Localizer3dOptions localizer_3d;
  /// The score's projection of the repeated path onto the taught one
  /// (teach_repeat/teach_repeat_metrics.h).
  teach_repeat::PathProjectionOptions path_projection;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    using teach_repeat::TeachMode;
    a->Visit("enabled", &enabled);
    a->VisitEnum("method", &method,
                 {{teach_repeat::ToString(TeachMode::k2d), TeachMode::k2d},
                  {teach_repeat::ToString(TeachMode::k3d), TeachMode::k3d}});
    a->Visit("map", &map);
    a->Visit("repeat_speed_mps", &repeat_speed_mps);
    a->Visit("repeat_turn_rate_deg_s", &repeat_turn_rate_deg_s);
    // FunnelLaneOptions::max_milestone_overrun: 2D only, but a key of this level.
    a->Visit("max_milestone_overrun", &funnel_lane.max_milestone_overrun);
    a->Visit("start_offset", &start_offset);
    a->Visit("start_perturbation", &start_perturbation);
    a->Visit("occluders", &occluders);
    a->Visit("recovery_window_s", &recovery_window_s);
    a->Visit("stop_for_crossings", &stop_for_crossings);
    a->Visit("milestones", &milestones);
    a->Visit("funnel_lane", &funnel_lane);
    a->Visit("localizer_3d", &localizer_3d);
    a->Visit("path_projection", &path_projection);
  }
};

struct OutputsSpec {
  /// Camera images to save: none, or kitti (KITTI odometry layout in images/;
  /// needs robot.stereo.enabled).
  std::string save_images = "none";
  /// Whether the run folder gets run.mcap and metadata.yaml: the run as a ROS 2 bag
  /// (runner/run_bag.h, docs/mcap.md).
  bool mcap = true;
  /// Whether the bag also holds the camera images (PNG, as the stack receives them),
  /// which the run then saves in camera/ (needs mcap and robot.stereo.enabled).
  bool mcap_images = false;
  /// Keep every N-th row of the high-rate logs (the encoder-rate files and imu.csv;
  /// docs/run_folder.md), N >= 1; 1 keeps every row. The metrics and plots use every
  /// sample whatever N.
  int decimate = 1;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("save_images", &save_images);
    a->Visit("mcap", &mcap);
    a->Visit("mcap_images", &mcap_images);
    a->Visit("decimate", &decimate);
  }
};

/// What drives a closed-loop run: the scenario itself (its `drive` section, or
/// navigation), or a commander given from outside (a user's own, from C++ or the Python
/// module), which makes the `drive` section unused.
enum class DriveSource { kScenario, kExternal };

struct Scenario {
  std::uint64_t seed = 1;
  /// Simulated time limit [s], > 0, not counting the drive's start standstill
  /// (RunDuration). A path drive may end sooner.
  double duration_s = 60.0;
  SceneSpec scene;
  RobotSpec robot;
  DriveSpec drive;
  EstimationSpec estimation;
  NavigationSpec navigation;
  TeachRepeatSpec teach_repeat;
  OutputsSpec outputs;

  void Validate() const { Validate(DriveSource::kScenario); }
  /// With DriveSource::kExternal the `drive` section is not checked but for
  /// `drive.rate_hz` (> 0), the control rate a commander from outside may take.
  void Validate(DriveSource drive_source) const;
  /// Whether a run driven from `drive_source` carries the robot along a pose path
  /// (drive.mode pose_path, not navigating) instead of simulating its vehicle.
  bool CarriedOnPosePath(DriveSource drive_source) const;
  /// The run's simulated length [s]: duration_s, plus drive.start_standstill_s when the
  /// scenario drives the robot (drive_source kScenario): its drive, or closed-loop
  /// navigation (which starts after the standstill); not kinematic navigation.
  double RunDuration(DriveSource drive_source) const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("seed", &seed);
    a->Visit("duration_s", &duration_s);
    a->Visit("scene", &scene);
    a->Visit("robot", &robot);
    a->Visit("drive", &drive);
    a->Visit("estimation", &estimation);
    a->Visit("navigation", &navigation);
    a->Visit("teach_repeat", &teach_repeat);
    a->Visit("outputs", &outputs);
  }
};

/// `scenario` with every built-in material its terrain uses (the default and
/// the regions') copied into scene.terrain.materials with its parameters, unless
/// the scenario defines it already: the run folder's scenario.yaml then
/// reproduces the run after the built-in table changes.
Scenario WithBuiltinMaterialsResolved(Scenario scenario);

/// `scenario` with its robot's realism resolved: every imperfection key set (the
/// profile's where the file left it out) and as_built_seed set, so that the run
/// folder's scenario.yaml reproduces the robot after the profiles change.
Scenario WithRealismResolved(Scenario scenario);

/// The scene's objects: `scene.objects`, then each `scene.scatter` entry's,
/// scattered with its own stream of the run's seed, clear of the drive's
/// waypoints and the start.
std::vector<sim::StaticObject> SceneObjects(const Scenario& scenario);

}  // namespace trackbed::scenario
