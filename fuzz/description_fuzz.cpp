// Fuzzes the mapping of users' descriptions (description/) and of Gazebo heightmap
// images (assets/heightmap_reader): the input's first byte modulo 4 picks an SDF world
// (0), a URDF robot (1), a Gazebo sensor block put on a fixed skid-steer robot's
// camera link (2) or a heightmap image's bytes (3); the rest is its text or bytes.
//
// Finding: a crash, a sanitizer report, a hang, or an exception other than the
// documented description::DescriptionError / assets::AssetError (and OptionError from
// a mapped object's Validate); a mapped value that is not finite where Validate
// accepts the object; an albedo outside [0, 1]; a heightmap's height outside
// [pos.z, pos.z + size.z]; a range block's beams outside [1, a million]; a
// multicamera's baseline negative or not a number; a geodetic origin that passes its
// Validate with a normal gravity outside [9.7, 9.9] m/s² or an Earth rate of another
// magnitude than WGS 84's.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "fuzz_support.h"
#include "trackbed/assets/heightmap_reader.h"
#include "trackbed/common/option_error.h"
#include "trackbed/description/sdf_world.h"
#include "trackbed/description/urdf_robot.h"

namespace {

using trackbed::fuzz::Finding;
namespace description = trackbed::description;

constexpr const char* kTarget = "description_fuzz";

void Sdf(const std::string& text, const std::string& shapes_dir) {
  const description::SdfScene scene =
      description::ReadSdfWorldString(text, "fuzz.sdf", description::SdfWorldOptions{}, shapes_dir);
  for (const trackbed::sim::StaticObject& o : scene.objects) {
    try {
      o.Validate();
    } catch (const trackbed::OptionError&) {
      continue;  // the scenario's reader reports it, naming the key
    }
    if (!o.center_m.allFinite() || !std::isfinite(o.yaw_rad) || !std::isfinite(o.roll_rad) ||
        !std::isfinite(o.pitch_rad)) {
      Finding(kTarget, "an object passes Validate with a pose that is not finite");
    }
  }
  for (const trackbed::sim::StaticObject& o : scene.objects) {
    if (o.albedo && !(*o.albedo >= 0.0 && *o.albedo <= 1.0)) {
      Finding(kTarget, "an albedo outside [0, 1]: " + std::to_string(*o.albedo));
    }
  }
  if (scene.heightmap && !(scene.heightmap->size_m.minCoeff() > 0.0)) {
    Finding(kTarget, "a heightmap mapped with a size not > 0");
  }
  if (scene.geodetic_origin) {
    const trackbed::sim::GeodeticOrigin& g = *scene.geodetic_origin;
    bool valid = true;
    try {
      g.Validate();
    } catch (const trackbed::OptionError&) {
      valid = false;  // the scenario's reader reports it, naming the key
    }
    if (valid && !(g.NormalGravity() >= 9.7 && g.NormalGravity() <= 9.9)) {
      Finding(kTarget, "a geodetic origin's normal gravity " + std::to_string(g.NormalGravity()));
    }
    if (valid &&
        !(std::abs(g.EarthRateInWorld().norm() - trackbed::sim::wgs84::kEarthRateRadps) < 1e-15)) {
      Finding(kTarget, "a geodetic origin's Earth rate is not WGS 84's");
    }
  }
  if (scene.sun_elevation_deg && !(*scene.sun_elevation_deg > 0.0)) {
    Finding(kTarget, "a sun below the horizon: " + std::to_string(*scene.sun_elevation_deg));
  }
}

void Urdf(const std::string& text) {
  const description::UrdfRobot r =
      description::ReadUrdfRobotString(text, "fuzz.urdf", description::UrdfRobotOptions{});
  if (!(r.mass_kg > 0.0)) Finding(kTarget, "a robot mapped without a positive mass");
  if (r.station_x_m.size() < 2) Finding(kTarget, "a robot mapped with fewer than two stations");
  if (r.sensors.range && !(r.sensors.range->beams >= 1 && r.sensors.range->beams <= 1000000)) {
    Finding(kTarget, "a range block mapped to " + std::to_string(r.sensors.range->beams) +
                         " beams (1 to a million expected)");
  }
  if (r.sensors.camera && r.sensors.camera->baseline_m && !(*r.sensors.camera->baseline_m >= 0.0)) {
    Finding(kTarget, "a multicamera's baseline is negative or not a number");
  }
}

// A four-wheel robot whose camera link holds the fuzzed <gazebo> block's text.
void SensorBlock(const std::string& text) {
  std::string u =
      "<robot name='r'><link name='base_link'><inertial><mass value='10'/>"
      "<inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial>"
      "<collision><geometry><box size='0.6 0.4 0.2'/></geometry></collision></link>";
  for (int k = 0; k < 4; ++k) {
    const std::string n = "w" + std::to_string(k);
    u += "<link name='" + n +
         "'><collision><geometry><cylinder radius='0.1' length='0.05'/>"
         "</geometry></collision></link><joint name='" +
         n +
         "j' type='continuous'><parent "
         "link='base_link'/><child link='" +
         n + "'/><origin xyz='" + (k < 2 ? "0.2 " : "-0.2 ") + (k % 2 ? "0.25" : "-0.25") +
         " 0'/></joint>";
  }
  u += "<link name='camera_link'/><joint name='cj' type='fixed'><parent link='base_link'/>"
       "<child link='camera_link'/><origin xyz='0.2 0 0.2'/></joint>"
       "<gazebo reference='camera_link'>" +
       text + "</gazebo></robot>";
  Urdf(u);
}

// A heightmap image's bytes: the grid's heights between black and the brightest pixel.
void Heightmap(const std::string& bytes, const std::filesystem::path& dir) {
  trackbed::sim::HeightmapOptions o;
  o.file = (dir / "heightmap.png").string();
  o.size_m = Eigen::Vector3d(10, 8, 2);
  o.pos_m = Eigen::Vector3d(1, -2, 0.5);
  trackbed::fuzz::WriteFile(kTarget, o.file, bytes);
  const auto grid = trackbed::assets::ReadHeightmap(o);
  if (grid->min_height_m() < 0.5 || grid->max_height_m() > 2.5 + 1e-12) {
    Finding(kTarget, "a heightmap's heights outside [pos.z, pos.z + size.z]");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const trackbed::fuzz::ScratchDir dir("description");
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    switch (data[0] % 4) {
      case 0:
        Sdf(text, dir.path.string());
        break;
      case 1:
        Urdf(text);
        break;
      case 2:
        SensorBlock(text);
        break;
      default:
        Heightmap(text, dir.path);
    }
  } catch (const description::DescriptionError&) {
  } catch (const trackbed::assets::AssetError&) {
  }
  return 0;
}
