// Scenes for the renderer's and the camera's tests: a flat floor under a black sky lit
// by ambient light alone, and thin plates to see.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "trackbed/common/pinhole_camera.h"
#include "trackbed/render/renderer.h"
#include "trackbed/sim/world.h"

namespace trackbed::render::test {

/// A flat floor over `extent_m` (x_min, y_min, x_max, y_max) with `objects` on it.
inline sim::World FlatWorld(std::vector<sim::StaticObject> objects,
                            const Eigen::Vector4d& extent_m = {-2, -6, 12, 6}) {
  sim::TerrainOptions t;
  t.extent_m = extent_m;
  t.cell_size_m = 0.5;
  return sim::World(sim::WorldOptions{}, sim::Terrain(t, 1), std::move(objects));
}

/// Ambient light only (flat shading), a black sky, no tree crowns.
inline SceneAppearance AmbientOnly() {
  SceneAppearance a;
  a.ambient = 1.0;
  a.diffuse = 0.0;
  a.sky_gray = 0.0;
  a.tree_crowns = false;
  return a;
}

/// A thin plate facing −x (towards a camera looking along +x), its front face centred at
/// `c`, `width` across (y) and `height` tall (1 mm thick, so no other face shows).
inline sim::StaticObject Plate(const Eigen::Vector3d& c, double width, double height,
                               const std::string& appearance) {
  sim::StaticObject o;
  o.kind = "box";
  o.appearance = appearance;
  o.center_m = c.head<2>() + Eigen::Vector2d(0.0005, 0);  // front face at x = c.x
  o.base_z_m = c.z() - height / 2;
  o.size_m = {0.001, width, height};
  o.collides = false;
  return o;
}

/// A pinhole camera of `width` × `height` px, focal length `f` [px] on both axes, principal
/// point (`cx`, `cy`), without distortion.
inline geometry::PinholeCamera Pinhole(int width, int height, double f, double cx, double cy) {
  geometry::PinholeCamera K;
  K.width_px = width;
  K.height_px = height;
  K.fx = K.fy = f;
  K.cx = cx;
  K.cy = cy;
  return K;
}

/// A camera at `eye` looking along `forward` (not vertical) without roll: its x axis
/// level (OpenCV axes: x right, y down, z forward).
inline Eigen::Isometry3d Looking(const Eigen::Vector3d& eye, const Eigen::Vector3d& forward) {
  const Eigen::Vector3d z = forward.normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = z.cross(x);
  T.linear().col(2) = z;
  T.translation() = eye;
  return T;
}

}  // namespace trackbed::render::test
