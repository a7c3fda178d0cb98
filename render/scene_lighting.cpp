// The light map: the sun's shadows and the lit zones, baked once (see scene_lighting.h).
#include "trackbed/render/scene_lighting.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "trackbed/common/option_error.h"
#include "trackbed/common/units.h"
#include "trackbed/sim/world.h"

namespace trackbed::render {

void LightZone::Validate() const {
  option_check::Finite("center", center_m.x());
  option_check::Finite("center", center_m.y());
  option_check::Positive("size_m", size_m.x());
  option_check::Positive("size_m", size_m.y());
  option_check::Finite("yaw_deg", yaw_deg);
  option_check::InRange("gain", gain, 1e-3, 1e3);
  option_check::NonNegative("edge_m", edge_m);
}

double LightZone::Weight(double x, double y) const {
  // The signed distance to the rectangle (negative inside), in its own axes.
  const double yaw = units::Radians(yaw_deg), c = std::cos(yaw), s = std::sin(yaw);
  const double dx = x - center_m.x(), dy = y - center_m.y();
  const double qx = std::abs(c * dx + s * dy) - 0.5 * size_m.x();
  const double qy = std::abs(-s * dx + c * dy) - 0.5 * size_m.y();
  const double outside = std::hypot(std::max(qx, 0.0), std::max(qy, 0.0));
  const double distance = outside + std::min(std::max(qx, qy), 0.0);
  if (edge_m == 0.0) return distance <= 0.0 ? 1.0 : 0.0;
  const double a = std::clamp(0.5 - distance / edge_m, 0.0, 1.0);
  return a * a * (3.0 - 2.0 * a);
}

void SceneLighting::Validate() const {
  option_check::InRange("texel_m", texel_m, 0.02, 2.0);
  for (std::size_t k = 0; k < zones.size(); ++k) {
    option_check::Nested("zones[" + std::to_string(k) + "]", zones[k]);
  }
}

Eigen::Vector2i LightMap::Texel(double x, double y) const {
  return {std::clamp(static_cast<int>(std::floor((x - x_min) / texel_m)), 0, width - 1),
          std::clamp(static_cast<int>(std::floor((y - y_min) / texel_m)), 0, height - 1)};
}

std::size_t LightMap::Index(double x, double y) const {
  const Eigen::Vector2i t = Texel(x, y);
  return static_cast<std::size_t>(t.y()) * width + t.x();
}

Eigen::Vector3d SunDirection(double azimuth_deg, double elevation_deg) {
  const double az = units::Radians(azimuth_deg), el = units::Radians(elevation_deg);
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

double TreeCrownRadius(const sim::StaticObject& tree) { return std::max(0.6, tree.height_m / 3.0); }

namespace {

// Whether the ray p + s·d, s > 0, meets the sphere (c, r).
bool HitsSphere(const Eigen::Vector3d& p, const Eigen::Vector3d& d, const Eigen::Vector3d& c,
                double r) {
  const Eigen::Vector3d m = p - c;
  const double b = m.dot(d), q = m.squaredNorm() - r * r;
  if (q > 0.0 && b > 0.0) return false;  // outside and pointing away
  return b * b - q >= 0.0;
}

// Whether the ray meets the slab lo <= o + s·v <= hi for s in [*s0, *s1], narrowing it.
bool ClipSlab(double o, double v, double lo, double hi, double* s0, double* s1) {
  if (v == 0.0) return o >= lo && o <= hi;
  double a = (lo - o) / v, b = (hi - o) / v;
  if (a > b) std::swap(a, b);
  *s0 = std::max(*s0, a);
  *s1 = std::min(*s1, b);
  return *s0 <= *s1;
}

// Whether the ray meets the upright cylinder of `o` (its trunk or post).
bool HitsCylinder(const Eigen::Vector3d& p, const Eigen::Vector3d& d, const sim::StaticObject& o) {
  double s0 = 0.0, s1 = std::numeric_limits<double>::infinity();
  if (!ClipSlab(p.z(), d.z(), o.base_z_m, o.base_z_m + o.height_m, &s0, &s1)) return false;
  // |(p + s d − c)_xy|² <= r², a quadratic in s.
  const Eigen::Vector2d m = p.head<2>() - o.center_m, v = d.head<2>();
  const double a = v.squaredNorm(), b = m.dot(v), q = m.squaredNorm() - o.radius_m * o.radius_m;
  if (a == 0.0) return q <= 0.0;
  const double disc = b * b - a * q;
  if (disc < 0.0) return false;
  const double root = std::sqrt(disc);
  return std::max(s0, (-b - root) / a) <= std::min(s1, (-b + root) / a);
}

// Whether the ray meets the box of `o`.
bool HitsBox(const Eigen::Vector3d& p, const Eigen::Vector3d& d, const sim::StaticObject& o) {
  const double c = std::cos(o.yaw_rad), s = std::sin(o.yaw_rad);
  const Eigen::Vector2d m = p.head<2>() - o.center_m;
  const double px = c * m.x() + s * m.y(), py = -s * m.x() + c * m.y();
  const double dx = c * d.x() + s * d.y(), dy = -s * d.x() + c * d.y();
  double s0 = 0.0, s1 = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d h = 0.5 * o.size_m;
  return ClipSlab(px, dx, -h.x(), h.x(), &s0, &s1) && ClipSlab(py, dy, -h.y(), h.y(), &s0, &s1) &&
         ClipSlab(p.z(), d.z(), o.base_z_m, o.base_z_m + o.size_m.z(), &s0, &s1);
}

// The object's bounds in x, y and its top [m]: what its shadow can reach.
void Bounds(const sim::StaticObject& o, bool crown, Eigen::Vector2d* lo, Eigen::Vector2d* hi,
            double* top) {
  double reach = 0.0;
  if (o.shape == sim::StaticObject::Shape::kBox) {
    reach = 0.5 * o.size_m.head<2>().norm();
    *top = o.base_z_m + o.size_m.z();
  } else {
    reach = o.radius_m;
    *top = o.base_z_m + o.height_m;
    if (crown) {
      reach = std::max(reach, TreeCrownRadius(o));
      *top += TreeCrownRadius(o);
    }
  }
  *lo = o.center_m.array() - reach;
  *hi = o.center_m.array() + reach;
}

// Multiplies `map.sunlit` by the fraction of each texel's ground, in 2 × 2 points p
// (1 mm above the terrain), for which `blocked(p)` is false, over the texels the shadow
// of what spans [lo, hi] in plan, up to height `top`, can reach: it falls away from the
// sun, as far as the top's height above the lowest ground can be over the tangent of
// the elevation.
template <class Blocked>
void ShadeTexels(const sim::Terrain& terrain, const Eigen::Vector3d& sun, const Eigen::Vector2d& lo,
                 const Eigen::Vector2d& hi, double top, LightMap* map, Blocked&& blocked) {
  const double fall = (top - terrain.min_height_bound_m()) / std::max(sun.z(), 1e-3);
  const Eigen::Vector2d away = -sun.head<2>() * fall;
  const Eigen::Vector2d a = lo.cwiseMin(lo + away), b = hi.cwiseMax(hi + away);
  const Eigen::Vector2i first = map->Texel(a.x(), a.y()), last = map->Texel(b.x(), b.y());
  for (int j = first.y(); j <= last.y(); ++j) {
    for (int i = first.x(); i <= last.x(); ++i) {
      int lit = 0;
      for (int k = 0; k < 4; ++k) {
        const double x = map->x_min + (i + 0.25 + 0.5 * (k % 2)) * map->texel_m;
        const double y = map->y_min + (j + 0.25 + 0.5 * (k / 2)) * map->texel_m;
        lit += blocked(Eigen::Vector3d(x, y, terrain.Height(x, y) + 1e-3)) ? 0 : 1;
      }
      map->sunlit[static_cast<std::size_t>(j) * map->width + i] *= 0.25f * static_cast<float>(lit);
    }
  }
}

// Multiplies `map.sunlit` by the fraction of each texel's ground, in 2 × 2 points, that
// sees the sun past `o`: only the texels its shadow can reach are tested.
void CastShadow(const sim::World& world, const sim::StaticObject& o, bool crown,
                const Eigen::Vector3d& sun, LightMap* map) {
  Eigen::Vector2d lo, hi;
  double top = 0.0;
  Bounds(o, crown, &lo, &hi, &top);
  const bool tree = crown && o.kind == "tree";
  const Eigen::Vector3d crown_center(o.center_m.x(), o.center_m.y(), o.base_z_m + o.height_m);
  ShadeTexels(world.terrain(), sun, lo, hi, top, map, [&](const Eigen::Vector3d& p) {
    return o.shape == sim::StaticObject::Shape::kBox
               ? HitsBox(p, sun, o)
               : HitsCylinder(p, sun, o) ||
                     (tree && HitsSphere(p, sun, crown_center, TreeCrownRadius(o)));
  });
}

// Multiplies `map.sunlit` by the fraction of each texel's ground, in 2 × 2 points, that
// sees the sun past mesh object `m`'s triangles. They are sheared along the sun's rays
// (x, y moved by −z times the rays' run over rise), so that each ray towards the sun
// is vertical: a point's ray is blocked where the highest sheared triangle over it lies
// above the point.
void CastMeshShadow(const sim::World& world, const sim::MeshObject& m, const Eigen::Vector3d& sun,
                    LightMap* map) {
  const Eigen::Vector2d run = sun.head<2>() / sun.z();
  const Eigen::Isometry3d pose = m.Pose();
  sim::TriangleMesh sheared;
  sheared.triangles = m.visual->triangles;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3f& v : m.visual->vertices) {
    const Eigen::Vector3d w =
        pose * Eigen::Vector3d(v.cast<double>().cwiseProduct(m.entry.mesh.scale));
    box.extend(w);
    const Eigen::Vector2d q = w.head<2>() - w.z() * run;
    sheared.vertices.emplace_back(static_cast<float>(q.x()), static_cast<float>(q.y()),
                                  static_cast<float>(w.z()));
  }
  const sim::PlacedMesh placed(sheared, Eigen::Vector3d::Ones(), Eigen::Isometry3d::Identity());
  ShadeTexels(world.terrain(), sun, box.min().head<2>(), box.max().head<2>(), box.max().z(), map,
              [&](const Eigen::Vector3d& p) {
                const std::optional<double> top =
                    placed.HighestAt(p.x() - p.z() * run.x(), p.y() - p.z() * run.y());
                return top && *top > p.z();
              });
}

}  // namespace

LightMap BakeLightMap(const sim::World& world, const SceneLighting& lighting,
                      const Eigen::Vector3d& sun, bool tree_crowns) {
  lighting.Validate();
  const sim::Terrain& terrain = world.terrain();
  LightMap map;
  map.x_min = terrain.x_min();
  map.y_min = terrain.y_min();
  map.texel_m = lighting.texel_m;
  const double w = std::ceil((terrain.x_max() - terrain.x_min()) / lighting.texel_m);
  const double h = std::ceil((terrain.y_max() - terrain.y_min()) / lighting.texel_m);
  if (w * h > 16e6) {
    throw OptionError("lighting.texel_m", "gives a light map of " + std::to_string(w * h / 1e6) +
                                              " million texels over the terrain, beyond 16");
  }
  map.width = std::max(1, static_cast<int>(w));
  map.height = std::max(1, static_cast<int>(h));
  const std::size_t n = static_cast<std::size_t>(map.width) * map.height;
  map.sunlit.assign(n, 1.0f);
  map.gain.assign(n, 1.0f);
  for (int j = 0; j < map.height; ++j) {
    for (int i = 0; i < map.width; ++i) {
      const double x = map.x_min + (i + 0.5) * map.texel_m, y = map.y_min + (j + 0.5) * map.texel_m;
      double g = 1.0;
      for (const LightZone& z : lighting.zones) g *= 1.0 + (z.gain - 1.0) * z.Weight(x, y);
      map.gain[static_cast<std::size_t>(j) * map.width + i] = static_cast<float>(g);
    }
  }
  if (lighting.sun_shadows) {
    for (const sim::StaticObject& o : world.objects()) CastShadow(world, o, tree_crowns, sun, &map);
    for (const sim::MeshObject& m : world.meshes()) CastMeshShadow(world, m, sun, &map);
  }
  return map;
}

}  // namespace trackbed::render
