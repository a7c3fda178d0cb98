// Light that changes across a scene (`scene.appearance.lighting`): the sun's shadows
// of the scene's objects, and zones lit more or less than the rest (a lit doorway, a
// window-lit stretch of corridor, shade). Both are baked once into a light map over the
// terrain's extent, which the renderer reads per fragment by the fragment's world x, y:
//
//   grey = albedo · min(ambient + diffuse · max(n·sun, 0) · sunlit(x, y), 1) · gain(x, y)
//          · exposure
//
// sunlit(x, y) is the fraction of the texel's ground that sees the sun (2 × 2 rays per
// texel towards it, against tree crowns, trunks, posts, boxes, walls and the triangles
// of mesh objects): only the sun's direct light is shadowed, the sky's (ambient) is
// not. gain(x, y) is the product over the zones of 1 + (gain − 1) · w, w = 1 inside a
// zone and falling smoothly to 0 across `edge_m` about its border. Being a map in x
// and y, it lights a wall or a trunk by its footprint: a shadow or a lit zone covers
// whatever stands in it, to its full height.
// docs/camera_model.md ("Light that changes") has the sourced levels.
//
// With lighting the renderer's output is pre-exposed: the light is multiplied by the
// camera's exposure before the 8-bit output clips, so a zone brighter than the
// exposure can hold saturates as the sensor would, and an auto-exposure that shortens
// the exposure sees the texture again.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "trackbed/common/archive_eigen.h"

namespace trackbed::sim {
class World;
struct StaticObject;
}  // namespace trackbed::sim

namespace trackbed::render {

/// A region of the ground whose light is `gain` times the scene's.
struct LightZone {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();  ///< centre [m]
  Eigen::Vector2d size_m{1.0, 1.0};                    ///< extents along its axes [m], > 0
  double yaw_deg = 0.0;                                ///< rotation about z [deg]
  double gain = 1.0;                                   ///< light relative to the scene's, > 0
  double edge_m = 0.5;  ///< width of the soft border, centred on the rectangle's [m], >= 0

  void Validate() const;

  /// How much of the zone's gain applies at (x, y): 1 inside, 0 outside, a smoothstep
  /// across the border.
  double Weight(double x, double y) const;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("center", &center_m);
    a->Visit("size_m", &size_m);
    a->Visit("yaw_deg", &yaw_deg);
    a->Visit("gain", &gain);
    a->Visit("edge_m", &edge_m);
  }
};

/// `scene.appearance.lighting`.
struct SceneLighting {
  bool sun_shadows = true;  ///< the objects' shadows from the sun
  double texel_m = 0.1;     ///< the light map's resolution [m], in [0.02, 2]
  std::vector<LightZone> zones;

  void Validate() const;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("sun_shadows", &sun_shadows);
    a->Visit("texel_m", &texel_m);
    a->Visit("zones", &zones);
  }
};

/// The baked light over the terrain: texel (i, j) covers x in
/// [x_min + i·texel, x_min + (i + 1)·texel), the same in y.
struct LightMap {
  double x_min = 0.0, y_min = 0.0, texel_m = 1.0;
  int width = 0, height = 0;
  std::vector<float> sunlit;  ///< fraction of the texel that sees the sun, row-major (j, i)
  std::vector<float> gain;    ///< the zones' product, row-major (j, i)

  /// The texel (i, j) holding (x, y), clamped to the map.
  Eigen::Vector2i Texel(double x, double y) const;
  /// Its index in `sunlit` and `gain`.
  std::size_t Index(double x, double y) const;
};

/// The unit vector towards the sun, from azimuth (counter-clockwise from +x) and
/// elevation [deg].
Eigen::Vector3d SunDirection(double azimuth_deg, double elevation_deg);

/// The radius of the visual crown of a tree (the renderer draws it as a sphere centred
/// on the trunk's top).
double TreeCrownRadius(const sim::StaticObject& tree);

/// Bakes `lighting` for `world` lit from `sun` (unit, towards the sun), tree crowns
/// included when `tree_crowns`. Throws OptionError when the map would exceed 16 million
/// texels.
LightMap BakeLightMap(const sim::World& world, const SceneLighting& lighting,
                      const Eigen::Vector3d& sun, bool tree_crowns);

}  // namespace trackbed::render
