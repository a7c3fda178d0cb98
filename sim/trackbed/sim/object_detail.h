#pragma once
// Simpler far versions of a tree: its crown (a sphere) and trunk (a cylinder)
// drawn with fewer facets where the silhouette that loses moves by less than a
// bound in pixels (docs/rendering.md, "Objects at lower detail").
//
// A circle of radius r drawn as the regular polygon inscribed in it, one vertex
// every 2θ, lies inside the circle by at most r (1 − cos θ). Level 0 is the full
// version; a coarser level departs from it by the difference of the two, and at
// distance d with focal length f [px] that is f · extra / d pixels on screen.
#include <array>

namespace trackbed::sim {

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

/// How far the silhouette of `level` departs at most from level 0's, for a tree
/// whose crown has `crown_radius_m` (0: no crown) and whose trunk `trunk_radius_m`.
/// A sphere's silhouette sags by the coarser of its two steps: slices every 2π/n,
/// stacks every π/m, i.e. a polygon of n or 2m sides.
double TreeLevelExtraSag(double crown_radius_m, double trunk_radius_m,
                         const TreeTessellation& level);

/// The distance from which a silhouette that departs by `extra_sag_m` moves by less
/// than `max_error_px` at focal length `focal_px`: f · extra / max_error.
double FarVersionDistance(double extra_sag_m, double focal_px, double max_error_px);

}  // namespace trackbed::sim
