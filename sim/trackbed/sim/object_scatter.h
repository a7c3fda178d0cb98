// Procedural scatter: scene objects placed by density from the seed alone, so
// a large scene is a few lines of YAML (`scene.scatter`).
//
// The region is cut into square lattice cells of side 10/√density m (one cell
// per object at the asked density, in objects per 100 m²); each cell holds one
// candidate at a jittered place within its middle 60 % (so two are at least 0.4
// of a cell apart), with its size drawn from the given ranges. A candidate is
// kept unless its footprint comes within `clearance_m` of a keep-clear path or
// its centre lies on a material not listed. Every candidate is one SplitMix64
// stream of the seed and the cell's coordinates, so any part of an unbounded
// world can be scattered without the rest (the lattice is anchored at the
// world's origin, not at the region's corner).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "trackbed/sim/static_object.h"
#include "trackbed/sim/terrain.h"

namespace trackbed::sim {

/// `scene.scatter[k]`: one type of object scattered over a region.
struct ObjectScatter {
  /// Object type: tree, post or cylinder (upright cylinders), bench or box.
  std::string type = "tree";
  /// Mean objects per 100 m² before the keep-clear and material filters, in (0, 100].
  double density_per_100m2 = 1.0;
  /// Where [m]: x_min, y_min, x_max, y_max; all zero means the terrain's extent.
  Eigen::Vector4d region_m = Eigen::Vector4d::Zero();
  /// Cylinder radius range [m], min <= max.
  Eigen::Vector2d radius_m{0.15, 0.25};
  /// Height range [m], min <= max.
  Eigen::Vector2d height_m{3.0, 6.0};
  /// Box footprint: length and width [m] (yaw drawn uniformly).
  Eigen::Vector2d size_m{1.5, 0.5};
  /// Ground materials an object may stand on (by its centre); empty: any.
  std::vector<std::string> materials;
  /// Polylines [m] kept clear (the route): no footprint within `clearance_m` of them.
  std::vector<std::vector<Eigen::Vector2d>> keep_clear;
  /// Free distance between a footprint and a keep-clear path [m], >= 0.
  double clearance_m = 1.0;

  void Validate() const;
  /// The region scattered over `terrain` (its extent when `region_m` is all zero).
  Eigen::Vector4d RegionOn(const TerrainOptions& terrain) const;
  /// Lattice cells, one candidate each, over `terrain`: Validate's bound on it is
  /// checked with the terrain by the scene (at most kMaxCandidates).
  double Candidates(const TerrainOptions& terrain) const;
  static constexpr double kMaxCandidates = 1e6;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("type", &type);
    a->Visit("density_per_100m2", &density_per_100m2);
    a->Visit("region_m", &region_m);
    a->Visit("radius_m", &radius_m);
    a->Visit("height_m", &height_m);
    a->Visit("size_m", &size_m);
    a->Visit("materials", &materials);
    a->Visit("keep_clear", &keep_clear);
    a->Visit("clearance_m", &clearance_m);
  }
};

/// The objects `scatter` places with `stream_seed` on the terrain `terrain`
/// describes (its extent and material regions; no heights are built), in the
/// lattice cells whose candidates fall in `scatter`'s region. `extra_clear`
/// polylines are kept clear as `keep_clear` is. Deterministic; the order is
/// row by row of the lattice.
std::vector<StaticObject> ScatterObjects(
    const ObjectScatter& scatter, std::uint64_t stream_seed, const TerrainOptions& terrain,
    const std::vector<std::vector<Eigen::Vector2d>>& extra_clear = {});

}  // namespace trackbed::sim
