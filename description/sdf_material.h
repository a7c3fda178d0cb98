// An SDF visual's <material> as the grey albedo the cameras see (private to
// trackbed::description; docs/gazebo_users.md, "Colours").
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <sdf/Material.hh>

#include "sdf_geometry.h"

namespace trackbed::description {

/// An albedo map drawn as a pattern: the image and the colour it is multiplied by.
struct AlbedoPattern {
  std::string image_file;                     ///< Resolved, absolute.
  std::array<double, 3> diffuse = {1, 1, 1};  ///< Linear RGB, each in [0, 1].
};

/// The material's grey albedo in [0, 1] through the camera's grey conversion: Rec. 709's
/// luma weights (0.2126, 0.7152, 0.0722) on the linear red, green and blue of its
/// `<diffuse>`, times (where a PBR workflow gives an `<albedo_map>`) the mean over the
/// map's texels of the same weights on their sRGB-decoded channels, each scaled by the
/// diffuse channel (1 where no `<diffuse>` is given). Nothing when neither is given.
/// What of the material is not drawn goes to `unmapped`, each entry starting with
/// `where`. With `pattern` (the visual's shape can draw one: textured_unit_shapes.h),
/// an albedo map is returned there instead, and no albedo. Throws DescriptionError
/// starting with `where` for a map URI that cannot be resolved or an image OpenCV
/// cannot decode.
std::optional<double> MaterialAlbedo(const GeometryMapping& mapping, const sdf::Material& material,
                                     const std::string& where,
                                     std::optional<AlbedoPattern>* pattern,
                                     std::vector<std::string>* unmapped);

}  // namespace trackbed::description
