#pragma once
// Simpler far versions of a tree: its crown (a sphere) and trunk (a cylinder)
// drawn with fewer facets where its outline moves by less than a bound in pixels
// (docs/rendering.md, "far trees with fewer facets").
//
// Every vertex of a version lies on the true sphere or cylinder, so its outline lies
// between the true one and the true one moved in by its sag: how far its flattest facet
// lies inside (for a circle drawn as the inscribed polygon of n sides, r (1 − cos(π/n))).
// Two versions' outlines therefore differ by at most the larger sag, a coarser
// version's: at distance d and focal length f [px], f · sag / d pixels.
#include <array>

namespace trackbed::render {

/// The facets of one version of a tree.
struct TreeTessellation {
  int crown_slices;  ///< around the vertical axis
  int crown_stacks;  ///< from the bottom pole to the top
  int trunk_slices;  ///< around the trunk
};

/// Full (the versions the renderer drew before far versions existed), then coarser.
inline constexpr std::array<TreeTessellation, 3> kTreeLevels = {
    {{16, 10, 24}, {12, 8, 12}, {8, 5, 8}}};

/// How far inside a circle of `radius` the inscribed polygon of `sides` sides lies
/// at most: radius · (1 − cos(π / sides)).
double InscribedPolygonSag(double radius, int sides);

/// How far inside a sphere of `radius` drawn with `slices` × `stacks` facets (vertices
/// every 2π/slices of longitude and π/stacks of latitude) a facet lies at most:
/// radius · (1 − cos(π/slices) · cos(π/(2 stacks))), a band's facet at the equator.
double SphereSag(double radius, int slices, int stacks);

/// How far the outline of `level` can depart from level 0's (the full version's), for
/// a tree whose crown has `crown_radius_m` (0: no crown) and whose trunk
/// `trunk_radius_m`: the larger of the level's crown and trunk sags; 0 for level 0.
double TreeLevelDeparture(double crown_radius_m, double trunk_radius_m,
                          const TreeTessellation& level);

/// The distance from which an outline that departs by `departure_m` moves by less than
/// `max_error_px` at focal length `focal_px`: f · departure / max_error.
double FarVersionDistance(double departure_m, double focal_px, double max_error_px);

}  // namespace trackbed::render
