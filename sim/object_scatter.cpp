// Procedural scatter of scene objects (see object_scatter.h).
#include "trackbed/sim/object_scatter.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "trackbed/common/option_error.h"
#include "trackbed/common/split_mix.h"

namespace trackbed::sim {
namespace {

// Uniform in [0, 1) from a 64-bit hash (its top 53 bits).
double Unit(std::uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

void CheckRange(const char* name, const Eigen::Vector2d& range) {
  if (!(range.x() > 0.0 && range.y() >= range.x() && std::isfinite(range.y()))) {
    throw OptionError(name, "must be [min, max] with 0 < min <= max");
  }
}

// Distance from p to the segment a–b.
double SegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Distance from p to the nearest of the polylines (a single point is a polyline).
double PathDistance(const Eigen::Vector2d& p,
                    const std::vector<std::vector<Eigen::Vector2d>>& paths) {
  double d = std::numeric_limits<double>::infinity();
  for (const std::vector<Eigen::Vector2d>& path : paths) {
    for (std::size_t k = 0; k < path.size(); ++k) {
      d = std::min(d, SegmentDistance(p, path[k], path[std::min(k + 1, path.size() - 1)]));
    }
  }
  return d;
}

// The candidate of lattice cell (i, j): its shape drawn from `h`'s stream.
StaticObject Candidate(const ObjectScatter& s, const ObjectType& type, double cell_m,
                       std::int64_t i, std::int64_t j, std::uint64_t h) {
  StaticObject o;
  o.kind = s.type;
  o.shape = type.shape;
  o.appearance = type.appearance;
  h = split_mix::Mix(h);
  const double jx = 0.2 + 0.6 * Unit(h);
  h = split_mix::Mix(h);
  const double jy = 0.2 + 0.6 * Unit(h);
  o.center_m = {(static_cast<double>(i) + jx) * cell_m, (static_cast<double>(j) + jy) * cell_m};
  h = split_mix::Mix(h);
  const double height = s.height_m.x() + Unit(h) * (s.height_m.y() - s.height_m.x());
  h = split_mix::Mix(h);
  if (o.shape == StaticObject::Shape::kCylinder) {
    o.radius_m = s.radius_m.x() + Unit(h) * (s.radius_m.y() - s.radius_m.x());
    o.height_m = height;
  } else {
    o.size_m = {s.size_m.x(), s.size_m.y(), height};
    o.yaw_rad = 2.0 * M_PI * Unit(h);
  }
  return o;
}

// Radius of the circle around the centre that holds the footprint.
double FootprintRadius(const StaticObject& o) {
  return o.shape == StaticObject::Shape::kCylinder ? o.radius_m : 0.5 * o.size_m.head<2>().norm();
}

}  // namespace

void ObjectScatter::Validate() const {
  const ObjectType* t = FindObjectType(type);
  if (t == nullptr || type == "wall" || type == "door" || type == "poster" || type == "mesh" ||
      type == "car") {
    throw OptionError("type", "must be tree, post, cylinder, bench or box (got '" + type + "')");
  }
  option_check::InRange("density_per_100m2", density_per_100m2, 1e-6, 100.0);
  if (!region_m.isZero() && !(region_m[2] > region_m[0] && region_m[3] > region_m[1])) {
    throw OptionError("region_m", "must be [x_min, y_min, x_max, y_max] with max > min");
  }
  CheckRange("radius_m", radius_m);
  CheckRange("height_m", height_m);
  option_check::Positive("size_m[0]", size_m.x());
  option_check::Positive("size_m[1]", size_m.y());
  option_check::NonNegative("clearance_m", clearance_m);
  for (std::size_t k = 0; k < keep_clear.size(); ++k) {
    if (keep_clear[k].empty()) {
      throw OptionError("keep_clear[" + std::to_string(k) + "]", "must hold at least one point");
    }
  }
}

Eigen::Vector4d ObjectScatter::RegionOn(const TerrainOptions& terrain) const {
  return region_m.isZero() ? terrain.extent_m : region_m;
}

double ObjectScatter::Candidates(const TerrainOptions& terrain) const {
  const Eigen::Vector4d r = RegionOn(terrain);
  return (r[2] - r[0]) * (r[3] - r[1]) * density_per_100m2 / 100.0;
}

std::vector<StaticObject> ScatterObjects(
    const ObjectScatter& scatter, std::uint64_t stream_seed, const TerrainOptions& terrain,
    const std::vector<std::vector<Eigen::Vector2d>>& extra_clear) {
  scatter.Validate();
  const ObjectType& type = *FindObjectType(scatter.type);
  if (scatter.Candidates(terrain) > ObjectScatter::kMaxCandidates) {
    throw OptionError("density_per_100m2", "gives more than a million objects over the region");
  }
  const Eigen::Vector4d r = scatter.RegionOn(terrain);
  std::vector<std::vector<Eigen::Vector2d>> clear = scatter.keep_clear;
  clear.insert(clear.end(), extra_clear.begin(), extra_clear.end());
  const double cell = 10.0 / std::sqrt(scatter.density_per_100m2);
  const auto first = [cell](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
  std::vector<StaticObject> objects;
  for (std::int64_t j = first(r[1]); j <= first(r[3]); ++j) {
    for (std::int64_t i = first(r[0]); i <= first(r[2]); ++i) {
      const std::uint64_t h =
          split_mix::Mix(split_mix::Mix(stream_seed ^ static_cast<std::uint64_t>(i)) ^
                         static_cast<std::uint64_t>(j));
      StaticObject o = Candidate(scatter, type, cell, i, j, h);
      const Eigen::Vector2d& c = o.center_m;
      if (c.x() < r[0] || c.x() > r[2] || c.y() < r[1] || c.y() > r[3]) continue;
      if (PathDistance(c, clear) < FootprintRadius(o) + scatter.clearance_m) continue;
      if (!scatter.materials.empty() &&
          std::find(scatter.materials.begin(), scatter.materials.end(),
                    terrain.MaterialNameAt(c.x(), c.y())) == scatter.materials.end()) {
        continue;
      }
      objects.push_back(std::move(o));
    }
  }
  return objects;
}

}  // namespace trackbed::sim
