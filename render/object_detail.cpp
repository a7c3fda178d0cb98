// Far versions of trees (see object_detail.h).
#include "trackbed/render/object_detail.h"

#include <algorithm>
#include <cmath>

namespace trackbed::render {

double InscribedPolygonSag(double radius, int sides) {
  return radius * (1.0 - std::cos(M_PI / sides));
}

double SphereSag(double radius, int slices, int stacks) {
  return radius * (1.0 - std::cos(M_PI / slices) * std::cos(M_PI / (2.0 * stacks)));
}

double TreeLevelDeparture(double crown_radius_m, double trunk_radius_m,
                          const TreeTessellation& level) {
  const TreeTessellation& full = kTreeLevels[0];
  if (level.crown_slices == full.crown_slices && level.crown_stacks == full.crown_stacks &&
      level.trunk_slices == full.trunk_slices) {
    return 0.0;
  }
  return std::max(SphereSag(crown_radius_m, level.crown_slices, level.crown_stacks),
                  InscribedPolygonSag(trunk_radius_m, level.trunk_slices));
}

double FarVersionDistance(double departure_m, double focal_px, double max_error_px) {
  return focal_px * departure_m / max_error_px;
}

}  // namespace trackbed::render
