// The plant of one run (see plant.h).
#include "trackbed/runner/plant.h"

#include <utility>

#include "trackbed/assets/dem_reader.h"
#include "trackbed/assets/heightmap_reader.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/common/split_mix.h"
#include "trackbed/common/units.h"
#include "trackbed/robot/as_built.h"
#include "trackbed/robot/imu_parts.h"
#include "trackbed/robot/tracked_vehicle.h"

namespace trackbed::runner {
namespace {

// The carrier of a pose path: the drive's curve, the robot's weight and footprint.
robot::PosePathOptions PosePathOf(const scenario::Scenario& scenario) {
  const robot::TrackedVehicleOptions& v = scenario.robot.vehicle;
  robot::PosePathOptions o;
  o.waypoints = scenario.drive.waypoints;
  o.closed = scenario.drive.closed;
  o.laps = scenario.drive.laps;
  o.speed_mps = scenario.drive.pursuit.speed_mps;
  o.body_height_m = v.com_height_m;
  o.footprint_length_m = v.track_contact_length_m;
  o.footprint_width_m = v.track_gauge_m;
  o.mass_kg = v.mass_kg;
  o.stations_per_track =
      v.station_x_m.empty() ? v.road_wheels_per_track : static_cast<int>(v.station_x_m.size());
  return o;
}

// The stereo camera as built, its effects resolved by the realism profile.
std::unique_ptr<robot::StereoCamera> BuildCamera(const scenario::Scenario& scenario,
                                                 const RobotBuild& robot, const sim::World& world) {
  const scenario::RobotSpec& rs = scenario.robot;
  robot::StereoCameraSeeds seeds;
  seeds.scene = split_mix::Stream(scenario.seed, 2);
  seeds.noise = split_mix::Stream(scenario.seed, 3);
  seeds.pattern = split_mix::Stream(scenario.seed, 6);
  auto camera = std::make_unique<robot::StereoCamera>(
      robot::WithCameraEffectsResolved(rs.stereo, rs.realism), *robot.truth.stereo,
      robot.truth.imu.camera_time_offset_s, world, scenario.scene.appearance,
      scenario.scene.occluders, seeds);
  camera->SetBodyShape(robot::ShadowBoxes(rs.vehicle));
  return camera;
}

}  // namespace

Plant BuildPlant(const scenario::Scenario& scenario, const RobotBuild& robot, bool pose_path,
                 std::shared_ptr<sim::TrackMarks> track_marks) {
  const scenario::RobotSpec& rs = scenario.robot;
  const double gravity = scenario.scene.world.gravity_mps2;
  Plant p;
  const sim::TerrainOptions& terrain = scenario.scene.terrain;
  assets::SceneMeshes meshes = assets::LoadSceneMeshes(scenario::SceneObjects(scenario));
  // The heights under the roughness: an elevation model's, a heightmap's or the ground
  // meshes' (the scenario allows one of them).
  std::shared_ptr<const sim::ElevationGrid> base =
      assets::SampleMeshGround(meshes.grounds, terrain);
  if (terrain.dem.enabled()) base = assets::ReadDem(terrain.dem, terrain.grid_extent_m());
  if (terrain.heightmap) base = assets::ReadHeightmap(*terrain.heightmap);
  p.world = std::make_unique<sim::World>(
      scenario.scene.world, sim::Terrain(terrain, split_mix::Stream(scenario.seed, 0), base),
      std::move(meshes.primitives), std::move(meshes.obstacles));
  if (pose_path) {
    auto carrier = std::make_unique<robot::PosePathCarrier>(
        PosePathOf(scenario), &p.world->terrain(), robot.truth.vehicle, gravity);
    p.carrier = carrier.get();
    p.vehicle = std::move(carrier);
  } else {
    p.vehicle = std::make_unique<robot::TrackedVehicle>(
        rs.vehicle, p.world.get(), rs.start.x_m, rs.start.y_m, units::Radians(rs.start.yaw_deg),
        &robot.truth.vehicle);
  }
  p.encoders = std::make_unique<robot::SprocketEncoders>(rs.encoders);
  p.imu = std::make_unique<robot::Imu>(robot::WithImuPartResolved(rs.imu, rs.realism), gravity,
                                       split_mix::Stream(scenario.seed, 1), &robot.truth.imu);
  if (scenario.scene.geodetic_origin) {
    p.imu->SetEarthRate(scenario.scene.geodetic_origin->EarthRateInWorld());
  }
  if (rs.stereo.enabled) p.camera = BuildCamera(scenario, robot, *p.world);
  const std::optional<sim::TrackMarkOptions>& marks = scenario.scene.appearance.track_marks;
  if (marks && !pose_path) {
    p.track_marks =
        track_marks ? std::move(track_marks) : std::make_shared<sim::TrackMarks>(*marks);
    static_cast<robot::TrackedVehicle*>(p.vehicle.get())->SetTrackMarks(p.track_marks.get());
    if (p.camera) p.camera->SetTrackMarks(p.track_marks.get());
  }
  if (rs.range_sensor.enabled) {
    p.range_sensor =
        std::make_unique<robot::RangeSensor>(rs.range_sensor, split_mix::Stream(scenario.seed, 4));
  }
  return p;
}

}  // namespace trackbed::runner
