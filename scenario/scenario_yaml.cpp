// Scenario files: strict YAML reading with dotted-key errors, and exact writing.
//
// One field list per struct (the Visit functions below) drives both directions:
// the Reader walks a YAML map, reads each listed key with its full dotted path
// and rejects the keys nobody asked for; the Writer renders the same keys as
// text. Adding a scenario section is one Visit function plus one line in
// Visit(Scenario&). Scalars are parsed here (std::from_chars), not by yaml-cpp,
// so `010` is ten, `4096.5` is not an int and a quoted "0.1" is not a number.
#include "trackbed/scenario/scenario_yaml.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "trackbed/common/option_error.h"

namespace trackbed::scenario {

ScenarioError::ScenarioError(std::string source, std::string key, std::string reason)
    : std::runtime_error(source + ": " + (key.empty() ? "" : key + ": ") + reason),
      source_(std::move(source)),
      key_(std::move(key)),
      reason_(std::move(reason)) {}

namespace {

using sim::MaterialRegion;
using sim::StaticObject;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRadPerDeg = M_PI / 180.0;

double DegToRad(double deg) { return deg * kRadPerDeg; }

std::string Join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string Indexed(const std::string& path, std::size_t k) {
  return path + "[" + std::to_string(k) + "]";
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// ---------------------------------------------------------------------------
// Scalars: text <-> value.

// The shortest decimal that reads back as exactly `x`, with YAML's spellings of
// infinity and NaN. Plain notation unless it is more than 3 characters longer
// than exponent notation (200000 and 0.00001, but 1.0e-07). A mantissa without
// a dot gets ".0", which YAML 1.1 readers such as PyYAML need to see a float.
std::string FormatDouble(double x) {
  if (std::isnan(x)) return ".nan";
  if (std::isinf(x)) return x > 0 ? ".inf" : "-.inf";
  char buf[400];  // the longest shortest fixed forms (near 1.8e308, 5e-324) have < 330
  const char* end = std::to_chars(buf, buf + sizeof buf, x).ptr;
  const std::string shortest(static_cast<const char*>(buf), end);
  const std::to_chars_result fixed =
      std::to_chars(buf, buf + sizeof buf, x, std::chars_format::fixed);
  if (fixed.ec == std::errc() && fixed.ptr - buf <= static_cast<long>(shortest.size()) + 3) {
    return std::string(buf, fixed.ptr);
  }
  std::string s = shortest;
  const std::size_t e = s.find('e');
  if (e != std::string::npos && s.find('.') == std::string::npos) s.insert(e, ".0");
  return s;
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string WithoutPlus(const std::string& s) {
  return s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+' ? s.substr(1) : s;
}

std::optional<double> ParseDouble(const std::string& text) {
  const std::string s = WithoutPlus(text);
  const std::string lower = Lower(s);
  if (lower == ".inf") return kInf;
  if (lower == "-.inf") return -kInf;
  if (lower == ".nan") return std::numeric_limits<double>::quiet_NaN();
  double x = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

template <class Int>
std::optional<Int> ParseInteger(const std::string& text) {
  const std::string s = WithoutPlus(text);
  Int x = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return x;
}

std::optional<bool> ParseBool(const std::string& s) {
  if (s == "true" || s == "True" || s == "TRUE") return true;
  if (s == "false" || s == "False" || s == "FALSE") return false;
  return std::nullopt;
}

// Plain (unquoted) only when no YAML reader could take it for anything but this string.
bool IsPlainString(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
          c == '/')) {
      return false;
    }
  }
  static const std::set<std::string> kReserved = {"true", "false", "yes", "no",  "on",
                                                  "off",  "y",     "n",   "null"};
  return kReserved.count(Lower(s)) == 0;
}

std::string FormatString(const std::string& s) {
  if (IsPlainString(s)) return s;
  std::string out = "\"";
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// The degrees to write for a yaw of `rad` radians. Reading converts with
// DegToRad, which not every double is the image of; so take r = `rad` when some
// double d has DegToRad(d) == rad, else the nearest value that does, and write
// the shortest decimal among the doubles d with DegToRad(d) == r. Reading it
// gives r, whose degrees are again this text: the round trip is exact.
double YawDegreesFor(double rad) {
  if (!std::isfinite(rad) || rad == 0.0) return rad / kRadPerDeg;
  const auto up = [](double d) { return std::nextafter(d, kInf); };
  const auto down = [](double d) { return std::nextafter(d, -kInf); };
  double lo = rad / kRadPerDeg;  // within a few ulps of the answer
  for (int i = 0; i < 16 && DegToRad(lo) > rad; ++i) lo = down(lo);
  for (int i = 0; i < 16 && DegToRad(up(lo)) <= rad; ++i) lo = up(lo);
  const double below = DegToRad(lo), above = DegToRad(up(lo));
  const double target = rad - below <= above - rad ? below : above;
  double d = target == below ? lo : up(lo);
  for (int i = 0; i < 16 && DegToRad(down(d)) == target; ++i) d = down(d);
  double best = d;
  for (int i = 0; i < 16 && DegToRad(d) == target; ++i, d = up(d)) {
    if (FormatDouble(d).size() < FormatDouble(best).size()) best = d;
  }
  return best;
}

// ---------------------------------------------------------------------------
// The field lists. `v(key, field)` reads or writes one key; `v.Enum` maps an
// enum to names; `v.Either` picks between two groups of keys (reading: by which
// group the map uses; writing: by the flag).

template <class V>
void Visit(V& v, sim::WorldOptions& o) {
  v("physics_step_s", o.physics_step_s);
  v("gravity_mps2", o.gravity_mps2);
}

template <class V>
void Visit(V& v, sim::TerrainRoughness& o) {
  v("undulation_amplitude_m", o.undulation_amplitude_m);
  v("undulation_wavelength_m", o.undulation_wavelength_m);
  v("bump_amplitude_m", o.bump_amplitude_m);
  v("bump_wavelength_m", o.bump_wavelength_m);
  v("slope_x", o.slope_x);
  v("slope_y", o.slope_y);
}

template <class V>
void Visit(V& v, sim::TerrainMaterial& o) {
  v("name", o.name);
  v("cohesion_pa", o.cohesion_pa);
  v("friction_angle_deg", o.friction_angle_deg);
  v("shear_modulus_m", o.shear_modulus_m);
  v("bekker_kc", o.bekker_kc);
  v("bekker_kphi", o.bekker_kphi);
  v("bekker_n", o.bekker_n);
  v("lateral_shear_modulus_ratio", o.lateral_shear_modulus_ratio);
  v("lateral_strength_ratio", o.lateral_strength_ratio);
  v("unit_weight_npm3", o.unit_weight_npm3);
  v("albedo", o.albedo);
}

template <class V>
void Visit(V& v, sim::SoilVariationOptions& o) {
  v("amplitude", o.amplitude);
  v("correlation_length_m", o.correlation_length_m);
}

template <class V>
void Visit(V& v, MaterialRegion& o) {
  using Shape = MaterialRegion::Shape;
  v("material", o.material);
  v.Enum("shape", o.shape, {{"rectangle", Shape::kRectangle}, {"circle", Shape::kCircle}});
  if (o.shape == Shape::kRectangle) {
    v("min", o.min_m);
    v("max", o.max_m);
  } else {
    v("center", o.center_m);
    v("radius_m", o.radius_m);
  }
}

template <class V>
void Visit(V& v, sim::TerrainOptions& o) {
  v("extent_m", o.extent_m);
  v("cell_size_m", o.cell_size_m);
  v("roughness", o.roughness);
  v("default_material", o.default_material);
  v("materials", o.materials);
  v("regions", o.regions);
  v("soil_variation", o.soil_variation);
}

template <class V>
void Visit(V& v, sim::SceneAppearance& o) {
  v("sun_azimuth_deg", o.sun_azimuth_deg);
  v("sun_elevation_deg", o.sun_elevation_deg);
  v("ambient", o.ambient);
  v("diffuse", o.diffuse);
  v("sky_gray", o.sky_gray);
  v("ceiling_height_m", o.ceiling_height_m);
  v("tree_crowns", o.tree_crowns);
  v("texture_size_px", o.texture_size_px);
  v("terrain_full_detail_m", o.terrain_full_detail_m);
}

template <class V>
void Visit(V& v, sim::OccluderSpec& o) {
  v("waypoints", o.waypoints);
  v("speed_mps", o.speed_mps);
  v("start_s", o.start_s);
  v("back_and_forth", o.back_and_forth);
  v("height_m", o.height_m);
  v("radius_m", o.radius_m);
  v("appearance", o.appearance);
}

template <class V>
void Visit(V& v, SceneSpec& o) {
  v("name", o.name);
  v("world", o.world);
  v("terrain", o.terrain);
  v("objects", o.objects);  // StaticObject: its own Read and Render (see below)
  v("appearance", o.appearance);
  v("occluders", o.occluders);
}

template <class V>
void Visit(V& v, StartPose& o) {
  v("x_m", o.x_m);
  v("y_m", o.y_m);
  v("yaw_deg", o.yaw_deg);
}

template <class V>
void Visit(V& v, robot::SprocketMotorOptions& o) {
  v("time_constant_s", o.time_constant_s);
  v("velocity_gain_nm_per_radps", o.velocity_gain_nm_per_radps);
  v("max_torque_nm", o.max_torque_nm);
  v("max_speed_radps", o.max_speed_radps);
  v("inertia_kgm2", o.inertia_kgm2);
  v("viscous_friction_nm_per_radps", o.viscous_friction_nm_per_radps);
}

template <class V>
void Visit(V& v, robot::TrackedVehicleOptions& o) {
  v("mass_kg", o.mass_kg);
  v("hull_size_m", o.hull_size_m);
  v("com_height_m", o.com_height_m);
  v("ground_clearance_m", o.ground_clearance_m);
  v("track_gauge_m", o.track_gauge_m);
  v("track_width_m", o.track_width_m);
  v("track_contact_length_m", o.track_contact_length_m);
  v("sprocket_radius_m", o.sprocket_radius_m);
  v("road_wheels_per_track", o.road_wheels_per_track);
  v("station_x_m", o.station_x_m);
  using Contact = robot::TrackedVehicleOptions::Contact;
  v.Enum("contact", o.contact, {{"tracks", Contact::kTracks}, {"wheels", Contact::kWheels}});
  v("road_wheel_contact_length_m", o.road_wheel_contact_length_m);
  v("suspension_stiffness_npm", o.suspension_stiffness_npm);
  v("suspension_damping_nspm", o.suspension_damping_nspm);
  v("suspension_travel_m", o.suspension_travel_m);
  v("shear_damping_s", o.shear_damping_s);
  v("hull_contact_stiffness_npm", o.hull_contact_stiffness_npm);
  v("hull_friction", o.hull_friction);
  v("running_gear_resistance_coeff", o.running_gear_resistance_coeff);
  v("running_gear_speed_coeff_s_per_m", o.running_gear_speed_coeff_s_per_m);
  v("stall_time_s", o.stall_time_s);
  v("motor", o.motor);
}

template <class V>
void Visit(V& v, robot::EncoderOptions& o) {
  v("ticks_per_rev", o.ticks_per_rev);
  v("rate_hz", o.rate_hz);
}

template <class V>
void Visit(V& v, robot::ImuOptions& o) {
  v("rate_hz", o.rate_hz);
  v("gyro_noise_density", o.gyro_noise_density);
  v("gyro_bias_random_walk", o.gyro_bias_random_walk);
  v("accel_noise_density", o.accel_noise_density);
  v("accel_bias_random_walk", o.accel_bias_random_walk);
  v("gyro_initial_bias_std", o.gyro_initial_bias_std);
  v("accel_initial_bias_std", o.accel_initial_bias_std);
}

template <class V>
void Visit(V& v, robot::StereoRigOptions& o) {
  v("enabled", o.enabled);
  v("width_px", o.width_px);
  v("height_px", o.height_px);
  v("hfov_deg", o.hfov_deg);
  v("baseline_m", o.baseline_m);
  v("mount_m", o.mount_m);
  v("pitch_down_deg", o.pitch_down_deg);
  v("rate_hz", o.rate_hz);
  v("near_m", o.near_m);
  v("far_m", o.far_m);
  v("exposure", o.exposure);
  v("noise_std", o.noise_std);
  v("exposure_time_s", o.exposure_time_s);
  v("exposure_samples", o.exposure_samples);
  v("blackouts_s", o.blackouts_s);
}

template <class V>
void Visit(V& v, robot::RangeSensorOptions& o) {
  v("enabled", o.enabled);
  v("beams", o.beams);
  v("rate_hz", o.rate_hz);
  v("min_range_m", o.min_range_m);
  v("max_range_m", o.max_range_m);
  v("noise_std_m", o.noise_std_m);
  v("mount_m", o.mount_m);
}

template <class V>
void Visit(V& v, RobotSpec& o) {
  v("start", o.start);
  v("vehicle", o.vehicle);
  v("encoders", o.encoders);
  v("imu", o.imu);
  v("stereo", o.stereo);
  v("range_sensor", o.range_sensor);
}

template <class V>
void Visit(V& v, DriveCommand& o) {
  v("t_s", o.t_s);
  if (v.Either(o.track_speeds, {"v_mps", "yaw_rate_radps"}, {"left_mps", "right_mps"})) {
    v("left_mps", o.left_mps);
    v("right_mps", o.right_mps);
  } else {
    v("v_mps", o.v_mps);
    v("yaw_rate_radps", o.yaw_rate_radps);
  }
}

template <class V>
void Visit(V& v, DriveSpec& o) {
  using Mode = DriveSpec::Mode;
  v.Enum("mode", o.mode, {{"path", Mode::kPath}, {"script", Mode::kScript}});
  v("waypoints", o.waypoints);
  v("closed", o.closed);
  v("laps", o.laps);
  v("speed_mps", o.speed_mps);
  v("lookahead_m", o.lookahead_m);
  v("rate_hz", o.rate_hz);
  v("goal_tolerance_m", o.goal_tolerance_m);
  v("script", o.script);
}

template <class V>
void Visit(V& v, estimation::EkfOdometryOptions& o) {
  v("accel_noise", o.accel_noise);
  v("lateral_accel_noise", o.lateral_accel_noise);
  v("yaw_accel_noise", o.yaw_accel_noise);
  v("gyro_bias_walk", o.gyro_bias_walk);
  v("wheel_speed_std", o.wheel_speed_std);
  v("wheel_lateral_speed_std", o.wheel_lateral_speed_std);
  v("wheel_yaw_rate_std", o.wheel_yaw_rate_std);
  v("gyro_std", o.gyro_std);
  v("vo_speed_std", o.vo_speed_std);
  v("vo_yaw_rate_std", o.vo_yaw_rate_std);
  v("vo_reference_inliers", o.vo_reference_inliers);
}

template <class V>
void Visit(V& v, EstimationSpec& o) {
  v("enabled", o.enabled);
  v("icr_expansion", o.icr_expansion);
  v("icr_offset_m", o.icr_offset_m);
  v("slip_decay_time_s", o.slip_decay_time_s);
  v("slip_filter_time_s", o.slip_filter_time_s);
  v("min_inliers_for_slip", o.min_inliers_for_slip);
  v("fusion_rules", o.fusion_rules);
  v("fusion_weight_rise_time_s", o.fusion_weight_rise_time_s);
  v("vo_coast_time_s", o.vo_coast_time_s);
  v("vo_max_translation_per_frame_m", o.vo_max_translation_per_frame_m);
  v("vo_max_rotation_per_frame_deg", o.vo_max_rotation_per_frame_deg);
  v("vo_max_acceleration_mps2", o.vo_max_acceleration_mps2);
  v("vo_max_angular_acceleration_dps2", o.vo_max_angular_acceleration_dps2);
  v("vo_max_gyro_rotation_error_deg", o.vo_max_gyro_rotation_error_deg);
  v("ekf", o.ekf);
}

template <class V>
void Visit(V& v, NavigationObstacleSpec& o) {
  v("center", o.center);
  v("radius_m", o.radius_m);
}

template <class V>
void Visit(V& v, NavigationWallSpec& o) {
  v("from", o.from);
  v("to", o.to);
  v("radius_m", o.radius_m);
}

template <class V>
void Visit(V& v, NavigationSpec& o) {
  using Mode = NavigationSpec::Mode;
  v("enabled", o.enabled);
  v("method", o.method);
  v.Enum("mode", o.mode, {{"kinematic", Mode::kKinematic}, {"closed_loop", Mode::kClosedLoop}});
  v("goal", o.goal);
  v("obstacles", o.obstacles);
  v("walls", o.walls);
  v("field", o.field);
  v("field_seed", o.field_seed);
  v("safety_radius_m", o.safety_radius_m);
  v("footprint_radius_m", o.footprint_radius_m);
  v("control_period_s", o.control_period_s);
  v("wheel_radius_m", o.wheel_radius_m);
  v("wheel_separation_m", o.wheel_separation_m);
  v("max_wheel_speed_radps", o.max_wheel_speed_radps);
  v("stall_time_s", o.stall_time_s);
  v("pose_source", o.pose_source);
  v("max_speed_mps", o.max_speed_mps);
  v("max_yaw_rate_radps", o.max_yaw_rate_radps);
  v("stop_position_tolerance_m", o.stop_position_tolerance_m);
  v("stop_heading_tolerance_deg", o.stop_heading_tolerance_deg);
}

template <class V>
void Visit(V& v, TeachRepeatSpec& o) {
  v("enabled", o.enabled);
  v("method", o.method);
  v("map", o.map);
  v("repeat_speed_mps", o.repeat_speed_mps);
  v("repeat_turn_rate_deg_s", o.repeat_turn_rate_deg_s);
  v("start_offset", o.start_offset);
  v("start_perturbation", o.start_perturbation);
  v("occluders", o.occluders);
  v("recovery_window_s", o.recovery_window_s);
  v("stop_for_crossings", o.stop_for_crossings);
}

template <class V>
void Visit(V& v, OutputsSpec& o) {
  v("save_images", o.save_images);
}

template <class V>
void Visit(V& v, Scenario& o) {
  v("seed", o.seed);
  v("duration_s", o.duration_s);
  v("scene", o.scene);
  v("robot", o.robot);
  v("drive", o.drive);
  v("estimation", o.estimation);
  v("navigation", o.navigation);
  v("teach_repeat", o.teach_repeat);
  v("outputs", o.outputs);
}

// Object types: the `type` key picks the shape and the default appearance.
struct ObjectType {
  const char* name;
  StaticObject::Shape shape;
  const char* appearance;
};
constexpr ObjectType kObjectTypes[] = {
    {"wall", StaticObject::Shape::kBox, "plain_paint"},
    {"box", StaticObject::Shape::kBox, "plain_paint"},
    {"bench", StaticObject::Shape::kBox, "wood"},
    {"cylinder", StaticObject::Shape::kCylinder, "plain_paint"},
    {"tree", StaticObject::Shape::kCylinder, "bark"},
    {"post", StaticObject::Shape::kCylinder, "metal"},
    {"door", StaticObject::Shape::kBox, "door"},
    {"poster", StaticObject::Shape::kBox, "poster"},
};
// Doors and posters are dressing flat on a wall: drawn, not simulated, unless
// the file says `collides: true`.
bool DefaultCollides(const std::string& kind) { return kind != "door" && kind != "poster"; }

// A wall given by `from`/`to` without these keys.
constexpr double kWallThicknessM = 0.1;
constexpr double kWallHeightM = 2.5;

// ---------------------------------------------------------------------------
// Where a value came from: the file, or the override that set it.

// True when `key` is `prefix` or lies inside it (`prefix.x`, `prefix[2]`).
bool Within(const std::string& key, const std::string& prefix) {
  if (key.size() <= prefix.size()) return key == prefix;
  return key.compare(0, prefix.size(), prefix) == 0 &&
         (key[prefix.size()] == '.' || key[prefix.size()] == '[');
}

class Sources {
 public:
  explicit Sources(std::string file) : file_(std::move(file)) {}

  void AddOverride(std::string key, std::string source) {
    overrides_.emplace_back(std::move(key), std::move(source));
  }

  /// The last override that set `key`, a value inside it or a map on its way; else the file.
  const std::string& Of(const std::string& key) const {
    for (auto it = overrides_.rbegin(); it != overrides_.rend(); ++it) {
      if (Within(key, it->first) || Within(it->first, key)) return it->second;
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

std::string Describe(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Scalar:
      return n.Tag() == "!" ? "the quoted string \"" + n.Scalar() + "\"" : "'" + n.Scalar() + "'";
    case YAML::NodeType::Sequence:
      return "a list of " + std::to_string(n.size());
    case YAML::NodeType::Map:
      return "a map";
    default:
      return "nothing";
  }
}

// A plain (unquoted) scalar: the only kind that may hold a number or a bool.
bool IsPlainScalar(const YAML::Node& n) { return n.IsScalar() && n.Tag() != "!"; }

// ---------------------------------------------------------------------------
// Reading.

/// Reads one YAML map (null counts as empty) into a struct through its Visit.
class Reader {
 public:
  Reader(const Sources& sources, YAML::Node node, std::string path)
      : sources_(sources), node_(std::move(node)), path_(std::move(path)) {
    if (!node_.IsMap() && !node_.IsNull()) Fail(path_, "expected a map, got " + Describe(node_));
    if (!node_.IsMap()) return;
    std::set<std::string> seen;
    for (const auto& entry : node_) {
      if (!entry.first.IsScalar()) {
        Fail(path_, "expected names as keys, got " + Describe(entry.first));
      }
      if (!seen.insert(entry.first.Scalar()).second) {
        Fail(Join(path_, entry.first.Scalar()), "duplicate key");
      }
    }
  }

  template <class T>
  void operator()(const char* key, T& value) {
    if (const YAML::Node child = Take(key)) Read(child, Join(path_, key), value);
  }

  template <class E>
  void Enum(const char* key, E& value, std::initializer_list<std::pair<const char*, E>> names) {
    const YAML::Node child = Take(key);
    if (!child) return;
    std::string name;
    Read(child, Join(path_, key), name);
    std::vector<std::string> allowed;
    for (const auto& [n, e] : names) {
      if (name == n) {
        value = e;
        return;
      }
      allowed.emplace_back(n);
    }
    Fail(Join(path_, key), "must be one of " + JoinNames(allowed) + " (got '" + name + "')");
  }

  bool Either(bool& second, std::initializer_list<const char*> first_keys,
              std::initializer_list<const char*> second_keys) {
    const auto any = [this](std::initializer_list<const char*> keys) {
      return std::any_of(keys.begin(), keys.end(), [this](const char* k) { return Has(k); });
    };
    const bool a = any(first_keys), b = any(second_keys);
    if (a && b) {
      using Names = std::vector<std::string>;
      Fail(path_, "use either " + JoinNames(Names(first_keys.begin(), first_keys.end())) + " or " +
                      JoinNames(Names(second_keys.begin(), second_keys.end())) + ", not both");
    }
    if (a || b) second = b;
    return second;
  }

  bool Has(const char* key) const { return node_.IsMap() && node_[key].IsDefined(); }

  /// Rejects the keys no field asked for, listing those it did.
  void Finish() const {
    if (!node_.IsMap()) return;
    for (const auto& entry : node_) {
      const std::string key = entry.first.Scalar();
      if (std::find(asked_.begin(), asked_.end(), key) == asked_.end()) {
        Fail(Join(path_, key), "unknown key (allowed: " + JoinNames(asked_) + ")");
      }
    }
  }

 private:
  YAML::Node Take(const char* key) {
    asked_.emplace_back(key);
    return node_.IsMap() ? node_[key] : YAML::Node(YAML::NodeType::Undefined);
  }

  [[noreturn]] void Fail(const std::string& key, const std::string& reason) const {
    sources_.Fail(key, reason);
  }

  void Read(const YAML::Node& n, const std::string& path, double& out) const {
    const std::optional<double> x = IsPlainScalar(n) ? ParseDouble(n.Scalar()) : std::nullopt;
    if (!x) Fail(path, "expected a number, got " + Describe(n));
    out = *x;
  }

  void Read(const YAML::Node& n, const std::string& path, int& out) const {
    const std::optional<int> x = IsPlainScalar(n) ? ParseInteger<int>(n.Scalar()) : std::nullopt;
    if (!x) Fail(path, "expected an integer, got " + Describe(n));
    out = *x;
  }

  void Read(const YAML::Node& n, const std::string& path, std::uint64_t& out) const {
    const std::optional<std::uint64_t> x =
        IsPlainScalar(n) ? ParseInteger<std::uint64_t>(n.Scalar()) : std::nullopt;
    if (!x) Fail(path, "expected an integer in [0, 2^64), got " + Describe(n));
    out = *x;
  }

  void Read(const YAML::Node& n, const std::string& path, bool& out) const {
    const std::optional<bool> x = IsPlainScalar(n) ? ParseBool(n.Scalar()) : std::nullopt;
    if (!x) Fail(path, "expected true or false, got " + Describe(n));
    out = *x;
  }

  void Read(const YAML::Node& n, const std::string& path, std::string& out) const {
    if (!n.IsScalar()) Fail(path, "expected a string, got " + Describe(n));
    out = n.Scalar();
  }

  template <int N>
  void Read(const YAML::Node& n, const std::string& path, Eigen::Matrix<double, N, 1>& out) const {
    if (!n.IsSequence() || n.size() != N) {
      Fail(path, "expected a list of " + std::to_string(N) + " numbers, got " + Describe(n));
    }
    for (int i = 0; i < N; ++i) Read(n[i], Indexed(path, i), out[i]);
  }

  template <class T, class A>
  void Read(const YAML::Node& n, const std::string& path, std::vector<T, A>& out) const {
    if (n.IsNull()) {
      out.clear();
      return;
    }
    if (!n.IsSequence()) Fail(path, "expected a list, got " + Describe(n));
    out.clear();
    out.resize(n.size());
    for (std::size_t i = 0; i < n.size(); ++i) Read(n[i], Indexed(path, i), out[i]);
  }

  void Read(const YAML::Node& n, const std::string& path, StaticObject& out) const;

  template <class T>
  void Read(const YAML::Node& n, const std::string& path, T& out) const {
    Reader map(sources_, n, path);
    Visit(map, out);
    map.Finish();
  }

  const Sources& sources_;
  YAML::Node node_;
  std::string path_;
  std::vector<std::string> asked_;
};

void Reader::Read(const YAML::Node& n, const std::string& path, StaticObject& out) const {
  Reader map(sources_, n, path);
  map("type", out.kind);
  const auto type = std::find_if(std::begin(kObjectTypes), std::end(kObjectTypes),
                                 [&](const ObjectType& t) { return out.kind == t.name; });
  if (type == std::end(kObjectTypes)) {
    std::vector<std::string> names;
    for (const ObjectType& t : kObjectTypes) names.emplace_back(t.name);
    Fail(Join(path, "type"), "must be one of " + JoinNames(names) + " (got '" + out.kind + "')");
  }
  out.shape = type->shape;
  out.appearance = type->appearance;
  if (out.kind == "wall" && (map.Has("from") || map.Has("to"))) {
    if (!map.Has("from") || !map.Has("to")) {
      Fail(Join(path, map.Has("from") ? "to" : "from"),
           "missing: a wall given by from/to needs both");
    }
    Eigen::Vector2d from, to;
    double thickness_m = kWallThicknessM, height_m = kWallHeightM;
    map("from", from);
    map("to", to);
    map("thickness_m", thickness_m);
    map("height_m", height_m);
    const Eigen::Vector2d d = to - from;
    if (!(d.allFinite() && d.norm() > 0.0)) Fail(Join(path, "to"), "must differ from from");
    const std::pair<const char*, double> sizes[] = {{"thickness_m", thickness_m},
                                                    {"height_m", height_m}};
    for (const auto& [key, value] : sizes) {
      if (!(std::isfinite(value) && value > 0.0)) {
        Fail(Join(path, key), "must be > 0 (got " + option_check::Describe(value) + ")");
      }
    }
    out.center_m = 0.5 * (from + to);
    out.yaw_rad = std::atan2(d.y(), d.x());
    out.size_m = {d.norm(), thickness_m, height_m};
  } else if (out.shape == StaticObject::Shape::kBox) {
    double yaw_deg = 0.0;
    map("center", out.center_m);
    map("size_m", out.size_m);
    map("yaw_deg", yaw_deg);
    out.yaw_rad = DegToRad(yaw_deg);
  } else {
    map("center", out.center_m);
    map("radius_m", out.radius_m);
    map("height_m", out.height_m);
  }
  map("appearance", out.appearance);
  map("base_z_m", out.base_z_m);
  out.collides = DefaultCollides(out.kind);
  map("collides", out.collides);
  map.Finish();
}

// ---------------------------------------------------------------------------
// Writing.

/// A rendered value: its one-line form (scalar, flow list or flow map) and,
/// for maps and lists of maps, its block form (lines, unindented).
struct Text {
  std::string line;
  std::vector<std::string> block;
};

// Lists of maps are written one entry per line when every entry fits in this
// width; longer flow lists are wrapped to it.
constexpr std::size_t kMaxFlowWidth = 90;

/// Renders a struct through its Visit as a YAML map.
class Writer {
 public:
  template <class T>
  void operator()(const char* key, T& value) {
    Add(key, Render(value));
  }

  template <class E>
  void Enum(const char* key, E& value, std::initializer_list<std::pair<const char*, E>> names) {
    for (const auto& [name, e] : names) {
      if (e == value) Add(key, {name, {}});
    }
  }

  bool Either(bool& second, std::initializer_list<const char*>,
              std::initializer_list<const char*>) {
    return second;
  }

  void Add(const std::string& key, Text text) { entries_.emplace_back(key, std::move(text)); }

  Text Map() const {
    Text map;
    for (const auto& [key, text] : entries_) {
      map.line += (map.line.empty() ? "{" : ", ") + key + ": " + text.line;
      if (text.block.empty()) {
        map.block.push_back(key + ": " + text.line);
      } else {
        map.block.push_back(key + ":");
        for (const std::string& l : text.block) map.block.push_back("  " + l);
      }
    }
    map.line = map.line.empty() ? "{}" : map.line + "}";
    return map;
  }

 private:
  static Text Render(double x) { return {FormatDouble(x), {}}; }
  static Text Render(int x) { return {std::to_string(x), {}}; }
  static Text Render(std::uint64_t x) { return {std::to_string(x), {}}; }
  static Text Render(bool x) { return {x ? "true" : "false", {}}; }
  static Text Render(std::string& s) { return {FormatString(s), {}}; }

  template <int N>
  static Text Render(Eigen::Matrix<double, N, 1>& v) {
    std::string line;
    for (int i = 0; i < N; ++i) line += (i == 0 ? "[" : ", ") + FormatDouble(v[i]);
    return {line + "]", {}};
  }

  // Lists of maps as block lists (entries as flow maps when all fit), other lists as flow lists.
  template <class T, class A>
  static Text Render(std::vector<T, A>& values) {
    if (values.empty()) return {"[]", {}};
    Text list;
    std::vector<Text> entries;
    for (T& v : values) {
      entries.push_back(Render(v));
      list.line += (list.line.empty() ? "[" : ", ") + entries.back().line;
    }
    list.line += "]";
    if (entries.front().block.empty()) {
      if (list.line.size() > kMaxFlowWidth) list.block = Wrap(entries);
      return list;
    }
    const bool flow = std::all_of(entries.begin(), entries.end(),
                                  [](const Text& e) { return e.line.size() <= kMaxFlowWidth; });
    for (const Text& e : entries) {
      if (flow) list.block.push_back("- " + e.line);
      for (std::size_t i = 0; !flow && i < e.block.size(); ++i) {
        list.block.push_back((i == 0 ? "- " : "  ") + e.block[i]);
      }
    }
    return list;
  }

  // A long flow list over several lines, breaking between entries.
  static std::vector<std::string> Wrap(const std::vector<Text>& entries) {
    std::vector<std::string> lines = {"["};
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const std::string piece = entries[i].line + (i + 1 < entries.size() ? "," : "]");
      if (i > 0 && lines.back().size() + 1 + piece.size() > kMaxFlowWidth) lines.push_back(" ");
      lines.back() += (lines.back().size() > 1 ? " " : "") + piece;
    }
    return lines;
  }

  static Text Render(StaticObject& o) {
    Writer map;
    map("type", o.kind);
    map("center", o.center_m);
    if (o.shape == StaticObject::Shape::kBox) {
      map("size_m", o.size_m);
      double yaw_deg = YawDegreesFor(o.yaw_rad);
      map("yaw_deg", yaw_deg);
    } else {
      map("radius_m", o.radius_m);
      map("height_m", o.height_m);
    }
    map("appearance", o.appearance);
    if (std::isfinite(o.base_z_m)) map("base_z_m", o.base_z_m);
    if (o.collides != DefaultCollides(o.kind)) map("collides", o.collides);
    return map.Map();
  }

  template <class T>
  static Text Render(T& value) {
    Writer map;
    Visit(map, value);
    return map.Map();
  }

  std::vector<std::pair<std::string, Text>> entries_;
};

// ---------------------------------------------------------------------------
// Overrides.

struct PathStep {
  std::string key;  // empty for a list index
  std::size_t index = 0;
};

// Parses `a.b[2].c` or `a.b.2.c`; nullopt when malformed.
std::optional<std::vector<PathStep>> ParseKeyPath(const std::string& key) {
  const auto is_name_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  };
  const auto is_digits = [](const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
      return std::isdigit(static_cast<unsigned char>(c));
    });
  };
  const auto index_step = [&](const std::string& s) -> std::optional<PathStep> {
    const std::optional<std::size_t> i = is_digits(s) ? ParseInteger<std::size_t>(s) : std::nullopt;
    if (!i) return std::nullopt;
    return PathStep{"", *i};
  };
  std::vector<PathStep> steps;
  std::size_t i = 0;
  while (true) {
    std::size_t j = i;
    while (j < key.size() && is_name_char(key[j])) ++j;
    const std::string token = key.substr(i, j - i);
    if (token.empty()) return std::nullopt;
    if (is_digits(token)) {
      const std::optional<PathStep> step = index_step(token);
      if (!step) return std::nullopt;
      steps.push_back(*step);
    } else {
      steps.push_back({token, 0});
    }
    for (i = j; i < key.size() && key[i] == '[';) {
      j = key.find(']', i);
      const std::optional<PathStep> step =
          j == std::string::npos ? std::nullopt : index_step(key.substr(i + 1, j - i - 1));
      if (!step) return std::nullopt;
      steps.push_back(*step);
      i = j + 1;
    }
    if (i == key.size()) break;
    if (key[i] != '.') return std::nullopt;
    ++i;
  }
  if (steps.front().key.empty()) return std::nullopt;
  return steps;
}

// Sets the override's value in the tree, creating missing maps on the way.
void ApplyOverride(YAML::Node root, const Override& o, Sources* sources) {
  const std::string source = "--set " + o.key + "=" + o.value;
  const std::optional<std::vector<PathStep>> steps = ParseKeyPath(o.key);
  if (!steps) {
    throw ScenarioError(source, "", "expected a dotted key such as robot.vehicle.mass_kg");
  }
  std::string where;
  YAML::Node node = root;
  for (std::size_t s = 0; s < steps->size(); ++s) {
    const PathStep& step = (*steps)[s];
    YAML::Node child;
    if (step.key.empty()) {
      if (!node.IsSequence()) throw ScenarioError(source, where, "is not a list");
      if (step.index >= node.size()) {
        throw ScenarioError(source, where,
                            "index " + std::to_string(step.index) + " is past the end (" +
                                std::to_string(node.size()) + " entries)");
      }
      where = Indexed(where, step.index);
      child.reset(node[step.index]);
    } else {
      if (node.IsNull()) node = YAML::Node(YAML::NodeType::Map);
      if (!node.IsMap()) throw ScenarioError(source, where, "is not a map");
      where = Join(where, step.key);
      child.reset(node[step.key]);
    }
    if (s + 1 < steps->size()) {
      if (!child.IsDefined()) child = YAML::Node(YAML::NodeType::Map);
      node.reset(child);
      continue;
    }
    try {
      child = YAML::Load(o.value);
    } catch (const YAML::ParserException& e) {
      throw ScenarioError(source, where, "cannot parse the value as YAML: " + e.msg);
    }
  }
  sources->AddOverride(where, source);
}

// OptionError fields are struct member names; a few differ from their keys.
std::string KeyOfField(const std::string& field) {
  static const std::pair<const char*, const char*> kRenames[] = {
      {"center_m", "center"}, {"min_m", "min"}, {"max_m", "max"}, {"yaw_rad", "yaw_deg"}};
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
    key = Join(key, part);
    begin = end + 1;
  }
  return key;
}

}  // namespace

Override ParseOverride(const std::string& key_equals_value) {
  const std::size_t eq = key_equals_value.find('=');
  if (eq == std::string::npos || !ParseKeyPath(key_equals_value.substr(0, eq))) {
    throw std::invalid_argument("--set: expected key=value, got '" + key_equals_value + "'");
  }
  return {key_equals_value.substr(0, eq), key_equals_value.substr(eq + 1)};
}

Scenario ParseScenario(const std::string& yaml_text, const std::string& source_name,
                       const std::vector<Override>& overrides) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw ScenarioError(source_name, "",
                        e.mark.is_null()
                            ? "invalid YAML: " + e.msg
                            : "invalid YAML at line " + std::to_string(e.mark.line + 1) +
                                  ", column " + std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  Sources sources(source_name);
  if (root.IsNull()) root.reset(YAML::Node(YAML::NodeType::Map));
  if (!root.IsMap()) sources.Fail("", "expected a map of scenario keys, got " + Describe(root));
  for (const Override& o : overrides) ApplyOverride(root, o, &sources);

  Scenario scenario;
  Reader reader(sources, root, "");
  Visit(reader, scenario);
  reader.Finish();
  try {
    scenario.Validate();
  } catch (const OptionError& e) {
    sources.Fail(KeyOfField(e.field()), e.reason());
  }
  return scenario;
}

Scenario LoadScenario(const std::string& path, const std::vector<Override>& overrides) {
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
  Scenario scenario = ParseScenario(text, path, overrides);
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
  resolve("estimation.fusion_rules", &scenario.estimation.fusion_rules, false);
  resolve("teach_repeat.map", &scenario.teach_repeat.map, true);
  return scenario;
}

std::string ScenarioToYaml(const Scenario& scenario) {
  Scenario copy = scenario;  // Visit takes its fields by non-const reference
  Writer writer;
  Visit(writer, copy);
  std::string text;
  for (const std::string& line : writer.Map().block) text += line + "\n";
  return text;
}

}  // namespace trackbed::scenario
