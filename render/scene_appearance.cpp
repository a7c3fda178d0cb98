// The scene appearance's checks (SceneAppearance in renderer.h).
#include <string>

#include "trackbed/common/option_error.h"
#include "trackbed/render/procedural_texture.h"
#include "trackbed/render/renderer.h"

namespace trackbed::render {

void SceneAppearance::Validate() const {
  option_check::InRange("sun_elevation_deg", sun_elevation_deg, 1.0, 90.0);
  option_check::Finite("sun_azimuth_deg", sun_azimuth_deg);
  option_check::InRange("ambient", ambient, 0.0, 1.0);
  option_check::InRange("diffuse", diffuse, 0.0, 1.0);
  option_check::InRange("sky_gray", sky_gray, 0.0, 1.0);
  option_check::NonNegative("terrain_full_detail_m", terrain_full_detail_m);
  option_check::NonNegative("object_far_error_px", object_far_error_px);
  option_check::NonNegative("ceiling_height_m", ceiling_height_m);
  if (lighting) option_check::Nested("lighting", *lighting);
  if (track_marks) option_check::Nested("track_marks", *track_marks);
  for (const std::string& name : classic_look_materials) {
    if (!HasTexture(name)) {
      throw OptionError("classic_look_materials", "'" + name + "' has no texture of its own");
    }
  }
  if (texture_size_px < 16 || texture_size_px > 2048 ||
      (texture_size_px & (texture_size_px - 1)) != 0) {
    throw OptionError("texture_size_px", "must be a power of two in [16, 2048] (got " +
                                             std::to_string(texture_size_px) + ")");
  }
}

}  // namespace trackbed::render
