// Corridor fittings as the renderer draws them (sim/corridor_fittings.h,
// render/corridor_fitting_textures.h, render/luminaire.h): a radiator the fittings
// place lands where the pinhole model puts it, a ceiling light's diffuser is drawn
// brighter than the ceiling around it, and the same scene renders to the same bytes.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/render/renderer.h"
#include "trackbed/sim/corridor_fittings.h"

namespace trackbed::render {
namespace {

namespace fs = sim::fitting_size;

geometry::PinholeCamera Camera() { return test::Pinhole(640, 480, 500.0, 319.0, 240.0); }

// The radiator the fittings place on a wall along x at y = 3 (its face at y = 2.95)
// facing a route along y = 0: radiators only.
sim::StaticObject PlacedRadiator() {
  sim::StaticObject wall;
  wall.kind = "wall";
  wall.center_m = {0.0, 3.0};
  wall.size_m = {10.0, 0.1, 2.5};
  wall.base_z_m = 0.0;
  sim::CorridorFittings spec;
  spec.skirting = spec.door_frames = spec.switches = spec.ceiling_lights = false;
  spec.notice_boards = spec.extinguishers = false;
  spec.radiator_spacing_m = 10.0;  // one on the wall
  const std::vector<sim::StaticObject> placed =
      sim::CorridorFittingObjects(spec, {wall}, {{-5.0, 0.0}, {5.0, 0.0}}, 0.0, 11);
  EXPECT_EQ(placed.size(), 1u);
  return placed.at(0);
}

// A level camera at (x, 0, height) looking along +y, the radiator alone before a black sky.
GrayImage Draw(const sim::StaticObject& radiator, double x, double height) {
  const sim::World world = test::FlatWorld({radiator}, {-6, -2, 6, 6});
  Renderer renderer(world, test::AmbientOnly(), {}, 5, 640, 480, 0.05, 100.0);
  GrayImage img;
  renderer.Render(Camera(), test::Looking({x, 0.0, height}, Eigen::Vector3d::UnitY()), 0.0, &img,
                  nullptr);
  return img;
}

TEST(CorridorFittingRenderTest, PlacedRadiatorLandsWherePinholeModelPredicts) {
  const sim::StaticObject r = PlacedRadiator();
  const geometry::PinholeCamera K = Camera();
  // The camera level with the radiator's middle, straight in front of it: only the
  // front face shows, its edges at the face's depth.
  const double mid = r.base_z_m + 0.5 * r.size_m.z();
  const double x = r.center_m.x();
  const GrayImage img = Draw(r, x, mid);
  const double depth = r.center_m.y() - 0.5 * r.size_m.y();
  const double left = K.cx - K.fx * 0.5 * r.size_m.x() / depth;
  const double right = K.cx + K.fx * 0.5 * r.size_m.x() / depth;
  const double top = K.cy - K.fy * 0.5 * r.size_m.z() / depth;
  const double bottom = K.cy + K.fy * 0.5 * r.size_m.z() / depth;
  // A pixel is drawn by its centre: the painted run's outer pixel edges lie within half
  // a pixel of the outline. The radiator's white (grey 195-226 with its channels) stands
  // above the floor's 178 and the black sky.
  const int row = static_cast<int>(K.cy) - 20, col = static_cast<int>(K.cx) + 7;
  int first = -1, last = -1, upper = -1, lower = -1;
  for (int u = 0; u < img.width; ++u) {
    if (img.at(u, row) > 188) last = u, first = first < 0 ? u : first;
  }
  for (int v = 0; v < img.height; ++v) {
    if (img.at(col, v) > 188) lower = v, upper = upper < 0 ? v : upper;
  }
  std::printf("radiator %.2f m: edges %+.3f / %+.3f / %+.3f / %+.3f px from the prediction\n",
              r.size_m.x(), first - 0.5 - left, last + 0.5 - right, upper - 0.5 - top,
              lower + 0.5 - bottom);
  EXPECT_NEAR(first - 0.5, left, 0.5);
  EXPECT_NEAR(last + 0.5, right, 0.5);
  EXPECT_NEAR(upper - 0.5, top, 0.5);
  EXPECT_NEAR(lower + 0.5, bottom, 0.5);
  // Its texture: a water channel every 50 mm, shaded (195) then lit (226) against the
  // plain panel (217), so about (length / 0.05) upward crossings of grey 206 along the row.
  int steps = 0;
  for (int u = first + 2; u < last - 2; ++u) {
    steps += img.at(u, row) < 206 && img.at(u + 1, row) >= 206;
  }
  EXPECT_NEAR(steps, r.size_m.x() / 0.05, 2.0);
}

TEST(CorridorFittingRenderTest, LuminaireIsBrighterThanTheCeilingAroundIt) {
  // A light under a 2.5 m ceiling, seen from 0.5 m up and 3 m away, in the corridor's
  // light (ambient 0.6, the "sun" 80 degrees up).
  sim::StaticObject light;
  light.kind = "luminaire";
  light.appearance = "luminaire";
  light.center_m = {3.0, 0.0};
  light.size_m = {fs::kLuminaireSideM, fs::kLuminaireSideM, fs::kLuminaireDepthM};
  light.base_z_m = 2.5 - fs::kLuminaireDepthM;
  light.collides = false;
  const sim::World world = test::FlatWorld({light}, {-2, -6, 12, 6});
  SceneAppearance a;
  a.ambient = 0.6;
  a.diffuse = 0.35;
  a.sun_elevation_deg = 80;
  a.ceiling_height_m = 2.5;
  Renderer renderer(world, a, {}, 5, 640, 480, 0.05, 100.0);
  GrayImage img;
  const Eigen::Vector3d up_ahead = Eigen::Vector3d(3.0, 0.0, 2.0).normalized();
  renderer.Render(Camera(), test::Looking({0.0, 0.0, 0.5}, up_ahead), 0.0, &img, nullptr);
  // The light's centre and a ceiling point 1 m beyond it, by the pinhole projection.
  const auto grey_at = [&](const Eigen::Vector3d& p_world) {
    const Eigen::Isometry3d T = test::Looking({0.0, 0.0, 0.5}, up_ahead);
    const Eigen::Vector3d p = T.inverse() * p_world;
    return img.at(static_cast<int>(std::lround(Camera().cx + Camera().fx * p.x() / p.z())),
                  static_cast<int>(std::lround(Camera().cy + Camera().fy * p.y() / p.z())));
  };
  const int diffuser = grey_at({3.0, 0.0, 2.48});
  const int ceiling = grey_at({4.5, 0.0, 2.5});
  std::printf("diffuser %d, ceiling %d\n", diffuser, ceiling);
  // Ambient plus the whole diffuse term on the diffuser (0.99): 252.45 (0.6 + 0.35 sin 80 deg)
  // = 238.5.
  EXPECT_NEAR(diffuser, 238.5, 1.5);
  EXPECT_GT(diffuser, ceiling + 80);
}

TEST(CorridorFittingRenderTest, TheSameSceneRendersToTheSameBytes) {
  const sim::StaticObject r = PlacedRadiator();
  const GrayImage a = Draw(r, r.center_m.x() - 0.4, 0.5);
  const GrayImage b = Draw(r, r.center_m.x() - 0.4, 0.5);
  EXPECT_EQ(a.pixels, b.pixels);
}

}  // namespace
}  // namespace trackbed::render
