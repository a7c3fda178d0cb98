// Far versions of trees (see object_detail.h).
#include "trackbed/sim/object_detail.h"

#include <algorithm>
#include <cmath>

namespace trackbed::sim {

double InscribedPolygonSag(double radius, int sides) {
  return radius * (1.0 - std::cos(M_PI / sides));
}

namespace {

double SphereSag(double radius, int slices, int stacks) {
  return InscribedPolygonSag(radius, std::min(slices, 2 * stacks));
}

}  // namespace

double TreeLevelExtraSag(double crown_radius_m, double trunk_radius_m,
                         const TreeTessellation& level) {
  const TreeTessellation& full = kTreeLevels[0];
  const double crown = SphereSag(crown_radius_m, level.crown_slices, level.crown_stacks) -
                       SphereSag(crown_radius_m, full.crown_slices, full.crown_stacks);
  const double trunk = InscribedPolygonSag(trunk_radius_m, level.trunk_slices) -
                       InscribedPolygonSag(trunk_radius_m, full.trunk_slices);
  return std::max({crown, trunk, 0.0});
}

double FarVersionDistance(double extra_sag_m, double focal_px, double max_error_px) {
  return focal_px * extra_sag_m / max_error_px;
}

}  // namespace trackbed::sim
