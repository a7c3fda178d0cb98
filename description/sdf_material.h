// An SDF visual's <material> as the grey albedo the cameras see (private to
// trackbed::description; docs/gazebo_users.md, "Colours").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <sdf/Material.hh>

#include "sdf_geometry.h"

namespace trackbed::description {

/// The material's grey albedo in [0, 1] through the camera's grey conversion: Rec. 709's
/// luma weights (0.2126, 0.7152, 0.0722) on the linear red, green and blue of its
/// `<diffuse>`, times (where a PBR workflow gives an `<albedo_map>`) the mean over the
/// map's texels of the same weights on their sRGB-decoded channels, each scaled by the
/// diffuse channel (1 where no `<diffuse>` is given). Nothing when neither is given.
/// What of the material is not drawn goes to `unmapped`, each entry starting with
/// `where`. Throws DescriptionError starting with `where` for a map URI that cannot be
/// resolved or an image OpenCV cannot decode.
std::optional<double> MaterialAlbedo(const GeometryMapping& mapping, const sdf::Material& material,
                                     const std::string& where, std::vector<std::string>* unmapped);

}  // namespace trackbed::description
