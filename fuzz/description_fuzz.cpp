// Fuzzes the mapping of users' descriptions (description/): the input's first byte
// picks an SDF world (even) or a URDF robot (odd), the rest is its text, read through
// sdformat or urdfdom and mapped onto scene objects or the vehicle's values.
//
// Finding: a crash, a sanitizer report, a hang, or an exception other than the
// documented description::DescriptionError (and OptionError from a mapped object's
// Validate); a mapped value that is not finite where Validate accepts the object.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
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
  if (scene.sun_elevation_deg && !(*scene.sun_elevation_deg > 0.0)) {
    Finding(kTarget, "a sun below the horizon: " + std::to_string(*scene.sun_elevation_deg));
  }
}

void Urdf(const std::string& text) {
  const description::UrdfRobot r =
      description::ReadUrdfRobotString(text, "fuzz.urdf", description::UrdfRobotOptions{});
  if (!(r.mass_kg > 0.0)) Finding(kTarget, "a robot mapped without a positive mass");
  if (r.station_x_m.size() < 2) Finding(kTarget, "a robot mapped with fewer than two stations");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const trackbed::fuzz::ScratchDir dir("description");
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    if (data[0] % 2 == 0) {
      Sdf(text, dir.path.string());
    } else {
      Urdf(text);
    }
  } catch (const description::DescriptionError&) {
  }
  return 0;
}
