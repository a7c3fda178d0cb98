// Validation of the scenario structs. Field names are the scenario file's keys
// (docs/scenario_format.md), so the YAML reader can report `robot.vehicle.mass_kg`
// straight from an OptionError.
#include "trackbed/scenario/scenario.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "trackbed/common/option_error.h"
#include "trackbed/common/split_mix.h"
#include "trackbed/render/terrain_detail.h"
#include "trackbed/sim/terrain_material.h"

namespace trackbed::scenario {
namespace {

// The streams of the scene's seed that scatter objects, one per `scene.scatter`
// entry from this one (the terrain's heights and soil use 0x4e16 and 0x5011).
constexpr std::uint64_t kScatterStream = 0x5ca7;
// The stream of the scene's seed that places the corridor fittings.
constexpr std::uint64_t kFittingsStream = 0xf177;

std::string Indexed(const std::string& name, std::size_t k) {
  return name + "[" + std::to_string(k) + "]";
}

void Finite(const std::string& field, double value) { option_check::Finite(field.c_str(), value); }

// The robot's start must be on the terrain: beyond its extent the chassis has no ground
// under it and falls. (A kinematic navigation run has no terrain and is not checked.)
void CheckStartOnTerrain(const Scenario& s) {
  const Eigen::Vector4d& e = s.scene.terrain.extent_m;
  const double x = s.robot.start.x_m, y = s.robot.start.y_m;
  if (x >= e[0] && x <= e[2] && y >= e[1] && y <= e[3]) return;
  throw OptionError("robot.start",
                    "(" + option_check::Describe(x) + ", " + option_check::Describe(y) +
                        ") is outside scene.terrain.extent_m [" + option_check::Describe(e[0]) +
                        ", " + option_check::Describe(e[1]) + ", " + option_check::Describe(e[2]) +
                        ", " + option_check::Describe(e[3]) + "]: no ground there");
}

// A commanded speed beyond the sprocket motors' top track speed (motor.max_speed_radps
// × sprocket_radius_m) can never be reached: refused rather than silently saturated.
// `track_mps` is the fastest track speed the command asks for.
void CheckTrackSpeed(const std::string& field, double track_mps, double top_mps) {
  if (std::abs(track_mps) <= top_mps) return;
  throw OptionError(field, "asks a track for " + option_check::Describe(std::abs(track_mps)) +
                               " m/s, beyond the motors' top track speed " +
                               option_check::Describe(top_mps) +
                               " m/s (robot.vehicle.motor.max_speed_radps × sprocket_radius_m)");
}

// A pose path's waypoints must be on the terrain: the carrier rests on the ground.
void CheckPosePathOnTerrain(const Scenario& s) {
  const Eigen::Vector4d& e = s.scene.terrain.extent_m;
  for (std::size_t k = 0; k < s.drive.waypoints.size(); ++k) {
    const Eigen::Vector2d& w = s.drive.waypoints[k];
    if (w.x() >= e[0] && w.x() <= e[2] && w.y() >= e[1] && w.y() <= e[3]) continue;
    throw OptionError("drive." + Indexed("waypoints", k),
                      "(" + option_check::Describe(w.x()) + ", " + option_check::Describe(w.y()) +
                          ") is outside scene.terrain.extent_m: a pose path rests on the ground");
  }
}

// Every speed the drive or the closed-loop navigator is told to reach.
void CheckCommandedSpeeds(const Scenario& s) {
  const robot::TrackedVehicleOptions& v = s.robot.vehicle;
  const double top = v.motor.max_speed_radps * v.sprocket_radius_m;
  if (s.navigation.enabled) {
    if (s.navigation.mode == NavigationSpec::Mode::kClosedLoop) {
      CheckTrackSpeed("navigation.max_speed_mps", s.navigation.max_speed_mps, top);
    }
    return;
  }
  if (s.drive.mode == DriveSpec::Mode::kPath) {
    CheckTrackSpeed("drive.speed_mps", s.drive.pursuit.speed_mps, top);
    return;
  }
  if (s.drive.mode == DriveSpec::Mode::kPosePath) return;  // carried, not driven
  for (std::size_t k = 0; k < s.drive.script.size(); ++k) {
    const DriveCommand& c = s.drive.script[k];
    const std::string at = "drive." + Indexed("script", k);
    if (c.track_speeds) {
      CheckTrackSpeed(at + ".left_mps", c.left_mps, top);
      CheckTrackSpeed(at + ".right_mps", c.right_mps, top);
    } else {  // converted with the nominal gauge: the faster track runs |v| + |ω|·W/2
      CheckTrackSpeed(at + ".v_mps",
                      std::abs(c.v_mps) + std::abs(c.yaw_rate_radps) * v.track_gauge_m / 2.0, top);
    }
  }
}

// Throws unless `name` is a built-in material or one the terrain defines.
void KnownMaterial(const std::string& field, const std::string& name,
                   const sim::TerrainOptions& terrain) {
  std::string known;
  for (const auto* list : {&sim::BuiltinMaterials(), &terrain.materials}) {
    for (const sim::TerrainMaterial& m : *list) {
      if (m.name == name) return;
      known += (known.empty() ? "" : ", ") + m.name;
    }
  }
  throw OptionError(field, "unknown material '" + name + "' (known: " + known + ")");
}

}  // namespace

void SceneSpec::Validate() const {
  if (name.empty()) throw OptionError("name", "must not be empty");
  if (geodetic_origin) option_check::Nested("geodetic_origin", *geodetic_origin);
  option_check::Nested("world", world);
  option_check::Nested("terrain", terrain);
  KnownMaterial("terrain.default_material", terrain.default_material, terrain);
  for (std::size_t k = 0; k < terrain.regions.size(); ++k) {
    KnownMaterial("terrain." + Indexed("regions", k) + ".material", terrain.regions[k].material,
                  terrain);
  }
  for (std::size_t k = 0; k < objects.size(); ++k) {
    option_check::Nested(Indexed("objects", k), objects[k]);
    if (objects[k].mesh.ground && terrain.heightmap) {
      throw OptionError(Indexed("objects", k) + ".ground",
                        "a ground mesh and terrain.heightmap exclude each other (both give the "
                        "heights)");
    }
    if (objects[k].mesh.ground && terrain.dem.enabled()) {
      throw OptionError(Indexed("objects", k) + ".ground",
                        "a ground mesh and terrain.dem exclude each other (both give the heights)");
    }
  }
  for (std::size_t k = 0; k < scatter.size(); ++k) {
    option_check::Nested(Indexed("scatter", k), scatter[k]);
    if (scatter[k].Candidates(terrain) > sim::ObjectScatter::kMaxCandidates) {
      throw OptionError(Indexed("scatter", k) + ".density_per_100m2",
                        "gives more than a million objects over the region");
    }
    for (std::size_t m = 0; m < scatter[k].materials.size(); ++m) {
      KnownMaterial(Indexed("scatter", k) + "." + Indexed("materials", m), scatter[k].materials[m],
                    terrain);
    }
  }
  if (fittings) {
    option_check::Nested("fittings", *fittings);
    if (fittings->ceiling_lights && !(appearance.ceiling_height_m > 0.0)) {
      throw OptionError("fittings.ceiling_lights",
                        "needs a ceiling (scene.appearance.ceiling_height_m > 0)");
    }
  }
  option_check::Nested("appearance", appearance);
  if (sdf) option_check::Nested("sdf", *sdf);
  for (std::size_t k = 0; k < occluders.size(); ++k) {
    option_check::Nested(Indexed("occluders", k), occluders[k]);
  }
}

void RobotSpec::Validate() const {
  option_check::Finite("start.x_m", start.x_m);
  option_check::Finite("start.y_m", start.y_m);
  option_check::Finite("start.yaw_deg", start.yaw_deg);
  option_check::Nested("vehicle", vehicle);
  option_check::Nested("encoders", encoders);
  option_check::Nested("imu", robot::WithImuPartResolved(imu, realism));
  option_check::Nested("stereo", stereo);
  option_check::Nested("range_sensor", range_sensor);
  option_check::Nested("imperfections", imperfections);
  if (description) option_check::Nested("description", *description);
}

std::uint64_t RobotSpec::AsBuiltSeed(std::uint64_t run_seed) const {
  return as_built_seed ? *as_built_seed : split_mix::Stream(run_seed, 5);
}

void DriveSpec::Validate() const {
  if (laps < 1) throw OptionError("laps", "must be >= 1 (got " + std::to_string(laps) + ")");
  pursuit.Validate();  // its keys are this map's
  option_check::Positive("rate_hz", rate_hz);
  option_check::InRange("start_standstill_s", start_standstill_s, 0.0, 1e6);
  if (mode == Mode::kPosePath && start_standstill_s > 0.0) {
    throw OptionError("start_standstill_s", "must be 0 with mode pose_path (nothing drives it)");
  }
  if (mode == Mode::kPath || mode == Mode::kPosePath) {
    const char* name = mode == Mode::kPath ? "path" : "pose_path";
    if (waypoints.size() < 2) {
      throw OptionError("waypoints", std::string("mode ") + name +
                                         " needs at least 2 waypoints (got " +
                                         std::to_string(waypoints.size()) + ")");
    }
    for (std::size_t k = 0; k < waypoints.size(); ++k) {
      if (!waypoints[k].allFinite()) {
        throw OptionError(Indexed("waypoints", k), "must be finite");
      }
      const std::size_t next = k + 1 < waypoints.size() ? k + 1 : 0;
      if (mode == Mode::kPosePath && (next != 0 || closed) &&
          (waypoints[next] - waypoints[k]).norm() < 1e-6) {
        throw OptionError(Indexed("waypoints", next),
                          "coincides with waypoint " + std::to_string(k) +
                              " (a pose path's curve needs distinct consecutive waypoints)");
      }
    }
    if (mode == Mode::kPosePath) {
      option_check::InRange("speed_mps", pursuit.speed_mps, 0.0, kMaxPosePathSpeedMps);
    }
  } else {
    if (script.empty()) throw OptionError("script", "mode script needs at least 1 command");
    for (std::size_t k = 0; k < script.size(); ++k) {
      const DriveCommand& c = script[k];
      const std::string at = Indexed("script", k);
      option_check::NonNegative((at + ".t_s").c_str(), c.t_s);
      if (k > 0 && c.t_s < script[k - 1].t_s) {
        throw OptionError(at + ".t_s", "must not be earlier than the previous command's t_s");
      }
      if (c.track_speeds) {
        Finite(at + ".left_mps", c.left_mps);
        Finite(at + ".right_mps", c.right_mps);
      } else {
        Finite(at + ".v_mps", c.v_mps);
        Finite(at + ".yaw_rate_radps", c.yaw_rate_radps);
      }
    }
  }
}

void EstimationSpec::Validate() const {
  option_check::InRange("icr_expansion", icr_expansion, 0.2, 5.0);
  localization.Validate();
}

const char* NavigationSpec::ToString(Field field) {
  switch (field) {
    case Field::kNone:
      return "none";
    case Field::kRandom:
      return "random";
    case Field::kPaperLeft:
      return "paper_left";
    case Field::kPaperRight:
      return "paper_right";
    case Field::kUTrap:
      return "u_trap";
    case Field::kNarrowGap:
      return "narrow_gap";
    case Field::kGoalBesideWall:
      return "goal_beside_wall";
    case Field::kNarrowCorridor:
      return "narrow_corridor";
  }
  return "unknown";
}

const char* NavigationSpec::ToString(PoseSource source) {
  switch (source) {
    case PoseSource::kFused:
      return "fused";
    case PoseSource::kWheelOdometry:
      return "wheel_odometry";
    case PoseSource::kGroundTruth:
      return "ground_truth";
  }
  return "unknown";
}

void NavigationSpec::Validate() const {
  Finite("goal.x_m", goal.x_m);
  Finite("goal.y_m", goal.y_m);
  Finite("goal.yaw_deg", goal.yaw_deg);
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    if (!obstacles[k].center.allFinite()) {
      throw OptionError(Indexed("obstacles", k) + ".center", "must be finite");
    }
    option_check::NonNegative((Indexed("obstacles", k) + ".radius_m").c_str(),
                              obstacles[k].radius_m);
  }
  for (std::size_t k = 0; k < walls.size(); ++k) {
    if (!walls[k].from.allFinite() || !walls[k].to.allFinite()) {
      throw OptionError(Indexed("walls", k), "from and to must be finite");
    }
    option_check::NonNegative((Indexed("walls", k) + ".radius_m").c_str(), walls[k].radius_m);
  }
  option_check::Positive("safety_radius_m", safety_radius_m);
  option_check::NonNegative("footprint_radius_m", footprint_radius_m);
  navigator.Validate();  // named by their keys: control_period_s, dwa.speed_samples, …
  option_check::Positive("max_speed_mps", max_speed_mps);
  option_check::Positive("max_yaw_rate_radps", max_yaw_rate_radps);
  option_check::Nested("kinematic", kinematic);
  option_check::Nested("clustering", clustering);
}

void TeachRepeatSpec::Validate() const {
  option_check::Positive("repeat_speed_mps", repeat_speed_mps);
  option_check::Positive("repeat_turn_rate_deg_s", repeat_turn_rate_deg_s);
  option_check::OffOrAtLeast("max_milestone_overrun", funnel_lane.max_milestone_overrun, 1.0);
  Finite("start_offset.x_m", start_offset.x_m);
  Finite("start_offset.y_m", start_offset.y_m);
  Finite("start_offset.yaw_deg", start_offset.yaw_deg);
  for (std::size_t k = 0; k < occluders.size(); ++k) {
    option_check::Nested(Indexed("occluders", k), occluders[k]);
    if (occluders[k].back_and_forth) {
      throw OptionError(Indexed("occluders", k) + ".back_and_forth",
                        "must be false: a crossing is one walk, scored as one place");
    }
  }
  option_check::NonNegative("recovery_window_s", recovery_window_s);
  option_check::Nested("milestones", milestones);
  option_check::Nested("funnel_lane", funnel_lane);
  option_check::Nested("localizer_3d", localizer_3d);
  option_check::Nested("path_projection", path_projection);
}

void OutputsSpec::Validate() const {
  if (save_images != "none" && save_images != "kitti") {
    throw OptionError("save_images", "must be none or kitti (got '" + save_images + "')");
  }
  if (decimate < 1) {
    throw OptionError("decimate", "must be >= 1 (got " + std::to_string(decimate) + ")");
  }
}

double Scenario::RunDuration(DriveSource drive_source) const {
  // The scenario's drive, or closed-loop navigation, starts after the standstill.
  const bool drives = drive_source == DriveSource::kScenario &&
                      (!navigation.enabled || navigation.mode == NavigationSpec::Mode::kClosedLoop);
  return duration_s + (drives ? drive.start_standstill_s : 0.0);
}

bool Scenario::CarriedOnPosePath(DriveSource drive_source) const {
  return drive_source == DriveSource::kScenario && !navigation.enabled &&
         drive.mode == DriveSpec::Mode::kPosePath;
}

void Scenario::Validate(DriveSource drive_source) const {
  if (!(std::isfinite(duration_s) && duration_s > 0.0 && duration_s <= 1e6)) {
    throw OptionError("duration_s",
                      "must be in (0, 1e6] (got " + option_check::Describe(duration_s) + ")");
  }
  option_check::Nested("scene", scene);
  option_check::Nested("robot", robot);
  // A navigation run drives itself, and a commander from outside replaces the drive:
  // the `drive` section is not used then.
  if (drive_source == DriveSource::kExternal) {
    option_check::Positive("drive.rate_hz", drive.rate_hz);
  } else if (!navigation.enabled) {
    option_check::Nested("drive", drive);
  }
  if (drive_source != DriveSource::kExternal) CheckCommandedSpeeds(*this);
  if (scene.fittings && drive.waypoints.empty()) {
    throw OptionError("scene.fittings", "needs drive.waypoints: the fittings face the route");
  }
  if (CarriedOnPosePath(drive_source)) CheckPosePathOnTerrain(*this);
  if (!(navigation.enabled && navigation.mode == NavigationSpec::Mode::kKinematic)) {
    CheckStartOnTerrain(*this);
  }
  option_check::Nested("estimation", estimation);
  option_check::Nested("navigation", navigation);
  option_check::Nested("teach_repeat", teach_repeat);
  if (teach_repeat.enabled) {
    if (!robot.stereo.enabled) {
      throw OptionError("teach_repeat.enabled", "teach & repeat needs robot.stereo.enabled: true");
    }
    if (navigation.enabled) {
      throw OptionError("teach_repeat.enabled", "teach & repeat and navigation exclude each other");
    }
    if (drive.mode == DriveSpec::Mode::kPosePath) {
      throw OptionError("teach_repeat.enabled",
                        "teach & repeat drives the robot; drive.mode pose_path carries it");
    }
  }
  option_check::Nested("outputs", outputs);
  if (navigation.enabled && navigation.mode == NavigationSpec::Mode::kClosedLoop) {
    if (!robot.range_sensor.enabled) {
      throw OptionError("robot.range_sensor.enabled",
                        "navigation.mode closed_loop needs the range sensor (set it true)");
    }
    using PoseSource = NavigationSpec::PoseSource;
    if (navigation.pose_source != PoseSource::kGroundTruth && !estimation.enabled) {
      throw OptionError("navigation.pose_source",
                        std::string(NavigationSpec::ToString(navigation.pose_source)) +
                            " needs estimation.enabled: true");
    }
    if (navigation.pose_source == PoseSource::kFused && !robot.stereo.enabled) {
      throw OptionError("navigation.pose_source", "fused needs robot.stereo.enabled: true");
    }
    if (navigation.field != NavigationSpec::Field::kNone || !navigation.obstacles.empty() ||
        !navigation.walls.empty()) {
      throw OptionError("navigation.mode",
                        "closed_loop senses the scene's objects; navigation.field, obstacles "
                        "and walls are for kinematic mode");
    }
  }
  if (robot.stereo.enabled && !(scene.appearance.terrain_full_detail_m > 0.0) &&
      scene.terrain.cells() > render::TerrainDetail::kMaxCells) {
    throw OptionError("scene.terrain.cell_size_m",
                      "gives " + option_check::Describe(scene.terrain.cells() / 1e6) +
                          " million cells; with scene.appearance.terrain_full_detail_m 0 the "
                          "camera's renderer meshes the whole grid and takes at most 16 million "
                          "(set it > 0 to draw a window in detail and the rest coarser)");
  }
  if (outputs.save_images == "kitti" && !robot.stereo.enabled) {
    throw OptionError("outputs.save_images", "kitti needs robot.stereo.enabled: true");
  }
  if (outputs.mcap_images && !(outputs.mcap && robot.stereo.enabled)) {
    throw OptionError("outputs.mcap_images",
                      "needs outputs.mcap: true and robot.stereo.enabled: true");
  }
}

Scenario WithRealismResolved(Scenario scenario) {
  RobotSpec& r = scenario.robot;
  r.imperfections = r.imperfections.Resolve(r.realism);
  r.stereo = robot::WithCameraEffectsResolved(r.stereo, r.realism);
  r.imu = robot::WithImuPartResolved(r.imu, r.realism);
  r.as_built_seed = r.AsBuiltSeed(scenario.seed);
  return scenario;
}

Scenario WithBuiltinMaterialsResolved(Scenario scenario) {
  sim::TerrainOptions& terrain = scenario.scene.terrain;
  std::vector<std::string> used = {terrain.default_material};
  for (const sim::MaterialRegion& r : terrain.regions) used.push_back(r.material);
  for (const std::string& name : used) {
    const auto defines = [&name](const sim::TerrainMaterial& m) { return m.name == name; };
    if (std::any_of(terrain.materials.begin(), terrain.materials.end(), defines)) continue;
    const auto& builtins = sim::BuiltinMaterials();
    const auto it = std::find_if(builtins.begin(), builtins.end(), defines);
    if (it != builtins.end()) terrain.materials.push_back(*it);
  }
  return scenario;
}

std::vector<sim::StaticObject> SceneObjects(const Scenario& scenario) {
  std::vector<sim::StaticObject> objects = scenario.scene.objects;
  std::vector<std::vector<Eigen::Vector2d>> clear = {
      {Eigen::Vector2d(scenario.robot.start.x_m, scenario.robot.start.y_m)}};
  std::vector<Eigen::Vector2d> route = scenario.drive.waypoints;
  if (scenario.drive.closed && !route.empty()) route.push_back(route.front());
  if (!route.empty()) clear.push_back(route);
  // The scene's streams come from the terrain's seed (runner/closed_loop.cpp).
  const std::uint64_t scene_seed = split_mix::Stream(scenario.seed, 0);
  for (std::size_t k = 0; k < scenario.scene.scatter.size(); ++k) {
    const std::vector<sim::StaticObject> more = sim::ScatterObjects(
        scenario.scene.scatter[k], split_mix::Stream(scene_seed, kScatterStream + k),
        scenario.scene.terrain, clear);
    objects.insert(objects.end(), more.begin(), more.end());
  }
  if (scenario.scene.fittings) {
    const std::vector<sim::StaticObject> more = sim::CorridorFittingObjects(
        *scenario.scene.fittings, objects, route, scenario.scene.appearance.ceiling_height_m,
        split_mix::Stream(scene_seed, kFittingsStream));
    objects.insert(objects.end(), more.begin(), more.end());
  }
  return objects;
}

}  // namespace trackbed::scenario
