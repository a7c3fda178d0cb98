// Scenario files through the config archive: strict reading with errors that name the
// file or the `--set` override a bad value came from, and exact writing.
//
// The keys are the structs' Serialize field lists (scenario.h and the options headers
// of sim, robot and estimation); the archive (trackbed/common/archive.h) reads and
// writes them. What is particular to scenario files stays here: scene objects' own
// file form, overrides and the attribution of each value to its source, validation's
// member names mapped to keys, and file names resolved against the scenario's folder.
#include "trackbed/scenario/scenario_yaml.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "trackbed/assets/dem_reader.h"
#include "trackbed/assets/heightmap_reader.h"
#include "trackbed/assets/scene_meshes.h"
#include "trackbed/common/archive.h"
#include "trackbed/common/option_error.h"
#include "trackbed/common/units.h"
#include "trackbed/description/sdf_world.h"
#include "trackbed/description/urdf_robot.h"
#include "trackbed/scenario/key_aliases.h"

namespace trackbed::scenario {

ScenarioError::ScenarioError(std::string source, std::string key, std::string reason)
    : std::runtime_error(source + ": " + (key.empty() ? "" : key + ": ") + reason),
      source_(std::move(source)),
      key_(std::move(key)),
      reason_(std::move(reason)) {}

namespace {

using archive::Node;
using sim::StaticObject;

constexpr archive::Wording kWording = archive::Wording::kDetailed;
constexpr double kInf = std::numeric_limits<double>::infinity();
// The degrees to write for a yaw of `rad` radians. Reading converts with
// units::Radians, which not every double is the image of; so take r = `rad` when some
// double d has units::Radians(d) == rad, else the nearest value that does, and write
// the shortest decimal among the doubles d with units::Radians(d) == r. Reading it
// gives r, whose degrees are again this text: the round trip is exact.
double YawDegreesFor(double rad) {
  if (!std::isfinite(rad) || rad == 0.0) return units::Degrees(rad);
  const auto up = [](double d) { return std::nextafter(d, kInf); };
  const auto down = [](double d) { return std::nextafter(d, -kInf); };
  double lo = units::Degrees(rad);  // within a few ulps of the answer
  for (int i = 0; i < 16 && units::Radians(lo) > rad; ++i) lo = down(lo);
  for (int i = 0; i < 16 && units::Radians(up(lo)) <= rad; ++i) lo = up(lo);
  const double below = units::Radians(lo), above = units::Radians(up(lo));
  const double target = rad - below <= above - rad ? below : above;
  double d = target == below ? lo : up(lo);
  for (int i = 0; i < 16 && units::Radians(down(d)) == target; ++i) d = down(d);
  double best = d;
  for (int i = 0; i < 16 && units::Radians(d) == target; ++i, d = up(d)) {
    if (archive::FormatDouble(d).size() < archive::FormatDouble(best).size()) best = d;
  }
  return best;
}

// ---------------------------------------------------------------------------
// Scene objects.

// The `type` key picks the shape and the default appearance (sim::ObjectTypes).
// Doors and posters are dressing flat on a wall: drawn, not simulated, unless
// the file says `collides: true`.
bool DefaultCollides(const std::string& kind) { return kind != "door" && kind != "poster"; }

// A wall given by `from`/`to` without these keys.
constexpr double kWallThicknessM = 0.1;
constexpr double kWallHeightM = 2.5;

// A wall given by its ends: a box along them.
void ReadWallEnds(archive::Reader& map, StaticObject* out) {
  if (!map.Has("from") || !map.Has("to")) {
    map.Fail(map.Has("from") ? "to" : "from", "missing: a wall given by from/to needs both");
  }
  Eigen::Vector2d from, to;
  double thickness_m = kWallThicknessM, height_m = kWallHeightM;
  map.Visit("from", &from);
  map.Visit("to", &to);
  map.Visit("thickness_m", &thickness_m);
  map.Visit("height_m", &height_m);
  const Eigen::Vector2d d = to - from;
  if (!(d.allFinite() && d.norm() > 0.0)) map.Fail("to", "must differ from from");
  const std::pair<const char*, double> sizes[] = {{"thickness_m", thickness_m},
                                                  {"height_m", height_m}};
  for (const auto& [key, value] : sizes) {
    if (!(std::isfinite(value) && value > 0.0)) {
      map.Fail(key, "must be > 0 (got " + option_check::Describe(value) + ")");
    }
  }
  out->center_m = 0.5 * (from + to);
  out->yaw_rad = std::atan2(d.y(), d.x());
  out->size_m = {d.norm(), thickness_m, height_m};
}

// A mesh: its file, full rotation, scale (one number or one per axis), collision
// solid and use as ground.
void ReadMeshKeys(archive::Reader& map, StaticObject* out) {
  sim::MeshSource& m = out->mesh;
  if (!map.Has("file")) map.Fail("file", "missing: a mesh names its file");
  map.Visit("file", &m.file);
  map.Visit("center", &out->center_m);
  double roll_deg = 0.0, pitch_deg = 0.0, yaw_deg = 0.0;
  map.Visit("roll_deg", &roll_deg);
  map.Visit("pitch_deg", &pitch_deg);
  map.Visit("yaw_deg", &yaw_deg);
  out->roll_rad = units::Radians(roll_deg);
  out->pitch_rad = units::Radians(pitch_deg);
  out->yaw_rad = units::Radians(yaw_deg);
  Node scale;
  map.Visit("scale", &scale);
  const std::string scale_path = archive::JoinKey(map.path(), "scale");
  if (scale.IsScalar()) {
    double uniform = 1.0;
    archive::Codec<double>::Read(scale, scale_path, map.wording(), &uniform);
    m.scale.setConstant(uniform);
  } else if (!scale.IsNull()) {
    archive::Codec<Eigen::Vector3d>::Read(scale, scale_path, map.wording(), &m.scale);
  }
  map.VisitEnum("collision", &m.collision,
                {{"mesh", sim::MeshSource::Collision::kMesh},
                 {"file", sim::MeshSource::Collision::kFile},
                 {"box", sim::MeshSource::Collision::kBox}});
  map.Visit("collision_file", &m.collision_file);
  map.Visit("ground", &m.ground);
}

void ReadObject(const Node& node, const std::string& path, archive::Wording wording,
                StaticObject* out) {
  archive::Reader map(node, path, wording);
  map.Visit("type", &out->kind);
  const sim::ObjectType* type = sim::FindObjectType(out->kind);
  if (type == nullptr) {
    std::vector<std::string> names;
    for (const sim::ObjectType& t : sim::ObjectTypes()) names.emplace_back(t.name);
    map.Fail("type",
             "must be one of " + archive::Reader::JoinNames(names) + " (got '" + out->kind + "')");
  }
  out->shape = type->shape;
  out->appearance = type->appearance;
  if (out->shape == StaticObject::Shape::kMesh) {
    ReadMeshKeys(map, out);
  } else if (out->kind == "wall" && (map.Has("from") || map.Has("to"))) {
    ReadWallEnds(map, out);
  } else if (out->shape == StaticObject::Shape::kBox) {
    double yaw_deg = 0.0;
    map.Visit("center", &out->center_m);
    map.Visit("size_m", &out->size_m);
    map.Visit("yaw_deg", &yaw_deg);
    out->yaw_rad = units::Radians(yaw_deg);
  } else {
    map.Visit("center", &out->center_m);
    map.Visit("radius_m", &out->radius_m);
    map.Visit("height_m", &out->height_m);
  }
  map.Visit("appearance", &out->appearance);
  map.Visit("albedo", &out->albedo);
  map.Visit("base_z_m", &out->base_z_m);
  out->collides = DefaultCollides(out->kind);
  map.Visit("collides", &out->collides);
  map.Finish();
}

// Walls are written as the boxes they are; base_z_m and collides only when they are
// not the defaults.
Node WriteObject(StaticObject o) {
  archive::Writer map;
  map.Visit("type", &o.kind);
  if (o.shape == StaticObject::Shape::kMesh) map.Visit("file", &o.mesh.file);
  map.Visit("center", &o.center_m);
  if (o.shape == StaticObject::Shape::kMesh) {
    double roll_deg = YawDegreesFor(o.roll_rad), pitch_deg = YawDegreesFor(o.pitch_rad),
           yaw_deg = YawDegreesFor(o.yaw_rad);
    map.Visit("roll_deg", &roll_deg);
    map.Visit("pitch_deg", &pitch_deg);
    map.Visit("yaw_deg", &yaw_deg);
    const Eigen::Vector3d& s = o.mesh.scale;
    if (s.x() == s.y() && s.x() == s.z()) {
      double uniform = s.x();
      map.Visit("scale", &uniform);
    } else {
      map.Visit("scale", &o.mesh.scale);
    }
    map.VisitEnum("collision", &o.mesh.collision,
                  {{"mesh", sim::MeshSource::Collision::kMesh},
                   {"file", sim::MeshSource::Collision::kFile},
                   {"box", sim::MeshSource::Collision::kBox}});
    if (!o.mesh.collision_file.empty()) map.Visit("collision_file", &o.mesh.collision_file);
    map.Visit("ground", &o.mesh.ground);
  } else if (o.shape == StaticObject::Shape::kBox) {
    map.Visit("size_m", &o.size_m);
    double yaw_deg = YawDegreesFor(o.yaw_rad);
    map.Visit("yaw_deg", &yaw_deg);
  } else {
    map.Visit("radius_m", &o.radius_m);
    map.Visit("height_m", &o.height_m);
  }
  map.Visit("appearance", &o.appearance);
  if (o.albedo) map.Visit("albedo", &*o.albedo);
  if (std::isfinite(o.base_z_m)) map.Visit("base_z_m", &o.base_z_m);
  if (o.collides != DefaultCollides(o.kind)) map.Visit("collides", &o.collides);
  return map.Take();
}

// ---------------------------------------------------------------------------
// Where a value came from: the file, or the override that set it.

class Sources {
 public:
  explicit Sources(std::string file) : file_(std::move(file)) {}

  void AddOverride(std::string key, std::string source) {
    overrides_.emplace_back(std::move(key), std::move(source));
  }

  /// The last override that set `key`, a value inside it or a map on its way; else the file.
  const std::string& Of(const std::string& key) const {
    for (auto it = overrides_.rbegin(); it != overrides_.rend(); ++it) {
      if (KeyWithin(key, it->first) || KeyWithin(it->first, key)) return it->second;
    }
    return file_;
  }

  [[noreturn]] void Fail(const std::string& key, const std::string& reason) const {
    throw ScenarioError(Of(key), key, reason);
  }

 private:
  std::string file_;
  std::vector<std::pair<std::string, std::string>> overrides_;  // (dotted key, "--set k=v")
};

// The aliases whose old key lies inside `dotted` (a value set there may use them).
std::vector<KeyAlias> AliasesWithin(const std::string& dotted) {
  std::vector<KeyAlias> within;
  for (const KeyAlias& alias : ScenarioKeyAliases()) {
    if (KeyWithin(alias.old_key, dotted) && alias.old_key != dotted) within.push_back(alias);
  }
  return within;
}

// Sets the override's value in the tree, creating missing maps on the way. A moved key
// (key_aliases.h) sets its new path, and so do moved keys inside a map it sets.
void ApplyOverride(Node& root, const Override& o, Sources* sources) {
  const std::string source = "--set " + OverrideText(o);
  const std::optional<archive::Path> path =
      archive::ParsePath(CurrentKey(o.key, ScenarioKeyAliases()));
  if (!path) {
    throw ScenarioError(source, "", "expected a dotted key such as robot.vehicle.mass_kg");
  }
  std::string where;
  try {
    Node& target = archive::Reach(root, *path, &where);
    target = archive::ParseYaml(o.value, where);
    MoveAliasedKeys(&root, AliasesWithin(where));
  } catch (const archive::SyntaxError& e) {
    throw ScenarioError(source, where, "cannot parse the value as YAML: " + e.detail());
  } catch (const archive::Error& e) {
    throw ScenarioError(source, e.path(), e.reason());
  }
  sources->AddOverride(where, source);
}

// OptionError fields are struct member names; a few differ from their keys.
std::string KeyOfField(const std::string& field) {
  static const std::pair<const char*, const char*> kRenames[] = {
      {"center_m", "center"}, {"min_m", "min"},         {"max_m", "max"},
      {"yaw_rad", "yaw_deg"}, {"roll_rad", "roll_deg"}, {"pitch_rad", "pitch_deg"}};
  std::string key;
  std::size_t begin = 0;
  while (begin <= field.size()) {
    std::size_t end = field.find('.', begin);
    if (end == std::string::npos) end = field.size();
    std::string part = field.substr(begin, end - begin);
    const std::string name = part.substr(0, part.find('['));
    for (const auto& [member, renamed] : kRenames) {
      if (name == member) part = renamed + part.substr(name.size());
    }
    key = archive::JoinKey(key, part);
    begin = end + 1;
  }
  return key;
}

// An elevation model must reach past the terrain's grid (its header says how far):
// checked when the scenario is read, so that the error names the scenario's key.
void CheckDemCoversTerrain(const std::string& path, const sim::TerrainOptions& terrain) {
  if (!terrain.dem.enabled()) return;
  const char* key = "scene.terrain.dem.file";
  assets::DemHeader h;
  try {
    h = assets::ReadDemHeader(terrain.dem);
  } catch (const assets::AssetError& e) {
    throw ScenarioError(path, key, e.what());
  }
  const Eigen::Vector4d g = terrain.grid_extent_m();
  const auto m = [](double v) { return option_check::Describe(v); };
  if (g[0] < h.first_m.x() || g[1] < h.first_m.y() || g[2] > h.last_m.x() || g[3] > h.last_m.y()) {
    throw ScenarioError(path, key,
                        terrain.dem.file + ": its pixel centres span x " + m(h.first_m.x()) +
                            " to " + m(h.last_m.x()) + " m and y " + m(h.first_m.y()) + " to " +
                            m(h.last_m.y()) +
                            " m around scene.terrain.dem.origin, short of the "
                            "terrain's grid [" +
                            m(g[0]) + ", " + m(g[1]) + ", " + m(g[2]) + ", " + m(g[3]) +
                            "] (scene.terrain.extent_m)");
  }
}

// The heightmap's image read once as the run will read it: an error names the key; its
// pixels' span must reach over the terrain's grid.
void CheckHeightmapCoversTerrain(const std::string& path, const sim::TerrainOptions& terrain) {
  if (!terrain.heightmap) return;
  const std::string key = "scene.terrain.heightmap.file";
  std::shared_ptr<const sim::ElevationGrid> grid;
  try {
    grid = assets::ReadHeightmap(*terrain.heightmap);
  } catch (const assets::AssetError& e) {
    throw ScenarioError(path, key, e.what());
  }
  const Eigen::Vector4d g = terrain.grid_extent_m();
  const double tolerance = 1e-9;  // [m]: the last pixel's centre is first + (n − 1) · spacing
  if (!grid->Covers(g[0] + tolerance, g[1] + tolerance, g[2] - tolerance, g[3] - tolerance)) {
    const auto m = [](double v) { return option_check::Describe(v); };
    throw ScenarioError(path, key,
                        terrain.heightmap->file + ": its pixels span x " + m(grid->first_m().x()) +
                            " to " + m(grid->last_m().x()) + " m and y " + m(grid->first_m().y()) +
                            " to " + m(grid->last_m().y()) + " m, short of the terrain's grid [" +
                            m(g[0]) + ", " + m(g[1]) + ", " + m(g[2]) + ", " + m(g[3]) +
                            "] (scene.terrain.extent_m)");
  }
}

// Every mesh object's files read once as they will be for the run: an error names the
// object's key; a ground mesh's plan must reach over the terrain's grid (the grid
// points it leaves without a triangle are found when the run samples it).
void CheckMeshes(const std::string& path, const Scenario& scenario) {
  const std::vector<StaticObject>& objects = scenario.scene.objects;
  const Eigen::Vector4d g = scenario.scene.terrain.grid_extent_m();
  Eigen::AlignedBox2d ground;
  std::string ground_key;
  for (std::size_t k = 0; k < objects.size(); ++k) {
    const StaticObject& o = objects[k];
    if (o.shape != StaticObject::Shape::kMesh) continue;
    const std::string key = "scene.objects[" + std::to_string(k) + "]";
    std::vector<StaticObject> one = {o};
    try {
      const assets::SceneMeshes m = assets::LoadSceneMeshes(one);
      if (!o.mesh.ground) continue;
      const sim::PlacedMesh placed(*m.grounds[0].visual, o.mesh.scale, m.grounds[0].Pose());
      ground.extend(
          Eigen::AlignedBox2d(placed.bounds().min().head<2>(), placed.bounds().max().head<2>()));
      ground_key = key + ".file";
    } catch (const assets::AssetError& e) {
      const bool collision = o.mesh.collision == sim::MeshSource::Collision::kFile &&
                             std::string(e.what()).rfind(o.mesh.collision_file + ":", 0) == 0;
      throw ScenarioError(path, key + (collision ? ".collision_file" : ".file"), e.what());
    }
  }
  if (!ground_key.empty() && !ground.contains(Eigen::AlignedBox2d(Eigen::Vector2d(g[0], g[1]),
                                                                  Eigen::Vector2d(g[2], g[3])))) {
    const auto m = [](double v) { return option_check::Describe(v); };
    throw ScenarioError(path, ground_key,
                        "the ground meshes span x " + m(ground.min().x()) + " to " +
                            m(ground.max().x()) + " m and y " + m(ground.min().y()) + " to " +
                            m(ground.max().y()) + " m, short of the terrain's grid [" + m(g[0]) +
                            ", " + m(g[1]) + ", " + m(g[2]) + ", " + m(g[3]) +
                            "] (scene.terrain.extent_m): a ground mesh must cover it");
  }
}

// The SDF world (scene.sdf) mapped into the scene once: its objects appended, its
// physics, gravity, geodetic origin, sun and ground friction set; `mapped` and `unmapped` recorded,
// so that a run folder's scenario.yaml, which holds the objects, is not mapped again.
void MapSdfWorld(const std::string& path, Scenario* scenario, DriveSource drive_source,
                 bool gravity_given) {
  std::optional<description::SdfWorldOptions>& sdf = scenario->scene.sdf;
  if (!sdf || sdf->mapped) return;
  description::SdfScene mapped;
  try {
    mapped = description::ReadSdfWorld(*sdf, description::DefaultShapesDir());
  } catch (const description::DescriptionError& e) {
    throw ScenarioError(path, "scene.sdf.file", e.what());
  }
  SceneSpec& scene = scenario->scene;
  scene.objects.insert(scene.objects.end(), mapped.objects.begin(), mapped.objects.end());
  if (mapped.physics_step_s) scene.world.physics_step_s = *mapped.physics_step_s;
  // The world's <gravity> as written wins; without one, a geodetic origin's normal
  // gravity unless the scenario gives the gravity; else sdformat's default, as before.
  if (mapped.geodetic_origin && !scene.geodetic_origin) {
    scene.geodetic_origin = mapped.geodetic_origin;
  } else if (mapped.geodetic_origin) {
    mapped.unmapped.push_back(sdf->file +
                              " <spherical_coordinates>: the scenario's scene.geodetic_origin "
                              "is kept");
  }
  if (mapped.gravity_mps2 && (mapped.gravity_explicit || !scene.geodetic_origin)) {
    scene.world.gravity_mps2 = *mapped.gravity_mps2;
  } else if (scene.geodetic_origin && !gravity_given) {
    scene.world.gravity_mps2 = scene.geodetic_origin->NormalGravity();
  }
  if (mapped.sun_azimuth_deg) scene.appearance.sun_azimuth_deg = *mapped.sun_azimuth_deg;
  if (mapped.sun_elevation_deg) scene.appearance.sun_elevation_deg = *mapped.sun_elevation_deg;
  if (mapped.ground_material) scene.terrain.default_material = *mapped.ground_material;
  if (mapped.heightmap) scene.terrain.heightmap = *mapped.heightmap;
  sdf->mapped = true;
  sdf->unmapped = std::move(mapped.unmapped);
  try {
    scenario->Validate(drive_source);
  } catch (const OptionError& e) {
    throw ScenarioError(path, "scene.sdf.file",
                        sdf->file + " maps onto " + KeyOfField(e.field()) + ": " + e.reason());
  }
}

// A description's camera and ray sensor blocks onto robot.stereo's and
// robot.range_sensor's keys (whether each is enabled stays the scenario's choice).
void MapSensorBlocks(const description::SensorBlocks& sensors, RobotSpec* robot) {
  if (sensors.camera) {
    const description::CameraSensorMapping& c = *sensors.camera;
    robot::StereoRigOptions& st = robot->stereo;
    st.width_px = c.width_px;
    st.height_px = c.height_px;
    st.hfov_deg = c.hfov_deg;
    st.focal_length_px.reset();  // the field of view gives it
    st.principal_point_px.reset();
    if (c.rate_hz) st.rate_hz = *c.rate_hz;
    st.near_m = c.near_m;
    st.far_m = c.far_m;
    if (c.noise_std) st.noise_std = *c.noise_std;
    if (c.baseline_m) st.baseline_m = *c.baseline_m;
    st.mount_m = c.mount_m;
    st.pitch_down_deg = c.pitch_down_deg;
  }
  if (sensors.range) {
    const description::RangeSensorMapping& r = *sensors.range;
    robot::RangeSensorOptions& rs = robot->range_sensor;
    rs.beams = r.beams;
    if (r.rate_hz) rs.rate_hz = *r.rate_hz;
    rs.min_range_m = r.min_range_m;
    rs.max_range_m = r.max_range_m;
    if (r.noise_std_m) rs.noise_std_m = *r.noise_std_m;
    rs.mount_m = r.mount_m;
  }
}

// The URDF robot (robot.description) mapped into the vehicle's keys and the stereo
// camera's mount once, recorded as `mapped` with what has no key.
void MapUrdfRobot(const std::string& path, Scenario* scenario, DriveSource drive_source) {
  std::optional<description::UrdfRobotOptions>& urdf = scenario->robot.description;
  if (!urdf || urdf->mapped) return;
  description::UrdfRobot r;
  try {
    r = description::ReadUrdfRobot(*urdf);
  } catch (const description::DescriptionError& e) {
    throw ScenarioError(path, "robot.description.file", e.what());
  }
  robot::TrackedVehicleOptions& v = scenario->robot.vehicle;
  v.mass_kg = r.mass_kg;
  v.hull_size_m = r.hull_size_m;
  v.com_height_m = r.com_height_m;
  v.ground_clearance_m = r.ground_clearance_m;
  v.track_gauge_m = r.track_gauge_m;
  v.track_width_m = r.track_width_m;
  v.sprocket_radius_m = r.sprocket_radius_m;
  v.station_x_m = r.station_x_m;
  v.contact = r.tracks ? robot::TrackedVehicleOptions::Contact::kTracks
                       : robot::TrackedVehicleOptions::Contact::kWheels;
  if (r.track_contact_length_m) v.track_contact_length_m = *r.track_contact_length_m;
  if (r.camera_mount_m) scenario->robot.stereo.mount_m = *r.camera_mount_m;
  if (r.camera_pitch_down_deg) scenario->robot.stereo.pitch_down_deg = *r.camera_pitch_down_deg;
  MapSensorBlocks(r.sensors, &scenario->robot);
  urdf->mapped = true;
  urdf->unmapped = std::move(r.unmapped);
  try {
    scenario->Validate(drive_source);
  } catch (const OptionError& e) {
    throw ScenarioError(path, "robot.description.file",
                        urdf->file + " maps onto " + KeyOfField(e.field()) + ": " + e.reason());
  }
}

}  // namespace

Override ParseOverride(const std::string& key_equals_value) {
  const std::size_t eq = key_equals_value.find('=');
  if (eq == std::string::npos || !archive::ParsePath(key_equals_value.substr(0, eq))) {
    throw std::invalid_argument("--set: expected key=value, got '" + key_equals_value + "'");
  }
  return {key_equals_value.substr(0, eq), key_equals_value.substr(eq + 1)};
}

std::string OverrideText(const Override& o) { return o.key + "=" + o.value; }

namespace {

// Whether the scenario's text (with its overrides) gives scene.world.gravity_mps2.
bool GivesGravity(const Node& root) {
  const Node* scene = root.Find("scene");
  const Node* world = scene != nullptr && scene->IsMap() ? scene->Find("world") : nullptr;
  return world != nullptr && world->IsMap() && world->Find("gravity_mps2") != nullptr;
}

// ParseScenario's work; `gravity_given` says whether the text gives the gravity.
Scenario ParseScenarioKeys(const std::string& yaml_text, const std::string& source_name,
                           const std::vector<Override>& overrides, DriveSource drive_source,
                           bool* gravity_given) {
  Sources sources(source_name);
  Node root;
  try {
    root = archive::ParseYaml(yaml_text);
  } catch (const archive::SyntaxError& e) {
    throw ScenarioError(source_name, "", e.reason());
  } catch (const archive::Error& e) {
    sources.Fail(e.path(), e.reason());
  }
  if (root.IsNull()) root = Node::Map();
  if (!root.IsMap()) {
    sources.Fail("", "expected a map of scenario keys, got " + archive::Describe(root, kWording));
  }
  try {
    MoveAliasedKeys(&root, ScenarioKeyAliases());
  } catch (const archive::Error& e) {
    sources.Fail(e.path(), e.reason());
  }
  for (const Override& o : overrides) ApplyOverride(root, o, &sources);

  Scenario scenario;
  try {
    archive::Read(root, "", kWording, &scenario);
  } catch (const archive::Error& e) {
    sources.Fail(e.path(), e.reason());
  }
  *gravity_given = GivesGravity(root);
  // A geodetic origin's normal gravity where the scenario gives none (a range error in
  // the origin is named by Validate, which checks it before the world).
  const std::optional<sim::GeodeticOrigin>& origin = scenario.scene.geodetic_origin;
  if (origin && !*gravity_given) scenario.scene.world.gravity_mps2 = origin->NormalGravity();
  try {
    scenario.Validate(drive_source);
  } catch (const OptionError& e) {
    sources.Fail(KeyOfField(e.field()), e.reason());
  }
  return scenario;
}

}  // namespace

Scenario ParseScenario(const std::string& yaml_text, const std::string& source_name,
                       const std::vector<Override>& overrides, DriveSource drive_source) {
  bool gravity_given = false;
  return ParseScenarioKeys(yaml_text, source_name, overrides, drive_source, &gravity_given);
}

Scenario LoadScenario(const std::string& path, const std::vector<Override>& overrides,
                      DriveSource drive_source) {
  const auto cannot_read = [&path](int error) {
    return ScenarioError(path, "", "cannot read file: " + std::generic_category().message(error));
  };
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) throw cannot_read(errno);
  std::string text;
  char buffer[1 << 14];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, n);
  if (std::ferror(file.get())) throw cannot_read(errno);
  bool gravity_given = false;
  Scenario scenario = ParseScenarioKeys(text, path, overrides, drive_source, &gravity_given);
  // Files a scenario names are relative to the scenario file, and stored
  // absolute, so that the resolved scenario.yaml in a run folder still finds them.
  const auto resolve = [&path](const char* key, std::string* value, bool folder) {
    if (value->empty()) return;
    std::filesystem::path p(*value);
    if (p.is_relative())
      p = std::filesystem::absolute(std::filesystem::path(path).parent_path() / p);
    p = p.lexically_normal();
    if (folder ? !std::filesystem::is_directory(p) : !std::filesystem::is_regular_file(p)) {
      throw ScenarioError(path, key, (folder ? "no such folder: " : "no such file: ") + p.string());
    }
    *value = p.string();
  };
  resolve("estimation.fusion.rules_file", &scenario.estimation.localization.fusion.rules_file,
          false);
  resolve("teach_repeat.map", &scenario.teach_repeat.map, true);
  resolve("robot.calibration_dir", &scenario.robot.calibration_dir, true);
  resolve("scene.terrain.dem.file", &scenario.scene.terrain.dem.file, false);
  if (scenario.scene.terrain.heightmap) {
    resolve("scene.terrain.heightmap.file", &scenario.scene.terrain.heightmap->file, false);
  }
  if (scenario.scene.sdf) {
    description::SdfWorldOptions& sdf = *scenario.scene.sdf;
    resolve("scene.sdf.file", &sdf.file, false);
    for (std::size_t k = 0; k < sdf.model_paths.size(); ++k) {
      resolve(("scene.sdf.model_paths[" + std::to_string(k) + "]").c_str(), &sdf.model_paths[k],
              true);
    }
    MapSdfWorld(path, &scenario, drive_source, gravity_given);
  }
  if (scenario.robot.description) {
    resolve("robot.description.file", &scenario.robot.description->file, false);
    MapUrdfRobot(path, &scenario, drive_source);
  }
  CheckDemCoversTerrain(path, scenario.scene.terrain);
  CheckHeightmapCoversTerrain(path, scenario.scene.terrain);
  for (std::size_t k = 0; k < scenario.scene.objects.size(); ++k) {
    sim::MeshSource& m = scenario.scene.objects[k].mesh;
    const std::string key = "scene.objects[" + std::to_string(k) + "].";
    resolve((key + "file").c_str(), &m.file, false);
    resolve((key + "collision_file").c_str(), &m.collision_file, false);
  }
  CheckMeshes(path, scenario);
  return scenario;
}

std::string ScenarioToYaml(const Scenario& scenario) {
  return archive::ToYaml(archive::Write(scenario));
}

}  // namespace trackbed::scenario

namespace trackbed::archive {

void Codec<sim::StaticObject>::Read(const Node& node, const std::string& path, Wording wording,
                                    sim::StaticObject* object) {
  scenario::ReadObject(node, path, wording, object);
}

Node Codec<sim::StaticObject>::Write(const sim::StaticObject& object) {
  return scenario::WriteObject(object);
}

}  // namespace trackbed::archive
