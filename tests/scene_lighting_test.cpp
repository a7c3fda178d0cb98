// Light that changes (render/scene_lighting.h): the baked shadows fall where the sun's
// geometry puts them, a zone's gain and the exposure scale the rendered grey levels, and
// the surface program with a light map draws what it draws without one where nothing
// changes.
#include "trackbed/render/scene_lighting.h"

#include <cmath>
#include <cstdio>
#include <functional>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/render/renderer.h"

namespace trackbed::render {
namespace {

sim::StaticObject Post(const Eigen::Vector2d& c, double radius, double height, const char* kind) {
  sim::StaticObject o;
  o.shape = sim::StaticObject::Shape::kCylinder;
  o.kind = kind;
  o.center_m = c;
  o.base_z_m = 0.0;
  o.radius_m = radius;
  o.height_m = height;
  return o;
}

TEST(SceneLightingTest, AZoneWeighsOneInsideZeroOutsideAndAHalfOnItsBorder) {
  LightZone z;
  z.center_m = {2, 1};
  z.size_m = {4, 2};
  z.yaw_deg = 90;  // 4 m along y, 2 m along x
  z.edge_m = 0.5;
  EXPECT_DOUBLE_EQ(z.Weight(2, 1), 1.0);
  EXPECT_DOUBLE_EQ(z.Weight(2, 2.7), 1.0);  // 0.3 m inside its long axis's end
  EXPECT_NEAR(z.Weight(3, 1), 0.5, 1e-12);  // on the border across
  EXPECT_NEAR(z.Weight(2, 3), 0.5, 1e-12);  // on the border along
  EXPECT_DOUBLE_EQ(z.Weight(3.3, 1), 0.0);  // beyond half the edge
  EXPECT_DOUBLE_EQ(z.Weight(2, -1.3), 0.0);
  z.edge_m = 0.0;
  EXPECT_DOUBLE_EQ(z.Weight(2.99, 1), 1.0);
  EXPECT_DOUBLE_EQ(z.Weight(3.01, 1), 0.0);
}

// A post and a tree in the sun from +x at 45°: each shadow lies towards −x, as long as
// the object is tall, as wide as it is; the crown's (a sphere) is an ellipse.
TEST(SceneLightingTest, ShadowsFallWhereTheSunsGeometryPutsThem) {
  const sim::World world = test::FlatWorld(
      {Post({0, 0}, 0.2, 2.0, "post"), Post({0, 6}, 0.1, 3.0, "tree")}, {-6, -3, 3, 9});
  SceneLighting lighting;
  lighting.texel_m = 0.05;
  const Eigen::Vector3d sun = SunDirection(0.0, 45.0);
  const LightMap map = BakeLightMap(world, lighting, sun, /*tree_crowns=*/true);
  const auto sunlit = [&map](double x, double y) { return map.sunlit[map.Index(x, y)]; };
  // The post: shadow from x = 0 to −2 (its height over tan 45°), 0.4 m wide.
  EXPECT_EQ(sunlit(-1.0, 0.0), 0.0f);
  EXPECT_EQ(sunlit(-1.9, 0.1), 0.0f);
  EXPECT_EQ(sunlit(-1.0, 0.3), 1.0f);
  EXPECT_EQ(sunlit(-2.4, 0.0), 1.0f);
  EXPECT_EQ(sunlit(1.0, 0.0), 1.0f);
  // The tree's crown, radius 1 m centred on the 3 m trunk's top: its shadow is centred
  // at x = −3, 1 m across y and 1.41 m (1 / sin 45°) along x.
  EXPECT_EQ(sunlit(-3.0, 6.8), 0.0f);
  EXPECT_EQ(sunlit(-3.0, 7.2), 1.0f);
  EXPECT_EQ(sunlit(-4.3, 6.0), 0.0f);
  EXPECT_EQ(sunlit(-4.6, 6.0), 1.0f);
  const LightMap bare = BakeLightMap(world, lighting, sun, /*tree_crowns=*/false);
  EXPECT_EQ(bare.sunlit[bare.Index(-3.6, 6.0)], 1.0f);  // beyond the trunk's shadow
  EXPECT_EQ(bare.sunlit[bare.Index(-2.0, 6.0)], 0.0f);  // the trunk's
  // A texel on a shadow's edge is partly lit.
  int partial = 0;
  for (const float s : map.sunlit) partial += (s > 0.0f && s < 1.0f);
  EXPECT_GT(partial, 0);
}

// A camera 3 m over the floor looking straight down, image x along world x.
Eigen::Isometry3d LookingDown(double x, double y) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  T.translation() = Eigen::Vector3d(x, y, 3.0);
  return T;
}

GrayImage RenderDown(const sim::World& world, const SceneAppearance& appearance, double exposure,
                     double x) {
  const geometry::PinholeCamera K = geometry::PinholeCamera::FromFieldOfView(160, 120, M_PI / 3);
  Renderer renderer(world, appearance, {}, 3, K.width_px, K.height_px, 0.05, 50.0);
  if (exposure != 1.0) renderer.SetExposure(exposure);
  GrayImage image;
  renderer.Render(K, LookingDown(x, 0.0), 0.0, &image, nullptr);
  return image;
}

// Over the columns whose world x passes `keep`, the largest |a − scale · b| [grey].
double WorstDifference(const GrayImage& a, const GrayImage& b, double scale,
                       const std::function<bool(int)>& keep) {
  double worst = 0.0;
  for (int v = 0; v < a.height; ++v) {
    for (int u = 0; u < a.width; ++u) {
      if (!keep(u)) continue;
      const std::size_t i = static_cast<std::size_t>(v) * a.width + u;
      worst = std::max(worst, std::abs(a.pixels[i] - scale * b.pixels[i]));
    }
  }
  return worst;
}

TEST(SceneLightingTest, TheLitProgramDrawsWhatTheUnlitOneDraws) {
  const sim::World world = test::FlatWorld({});
  SceneAppearance plain;
  plain.sun_elevation_deg = 60.0;
  plain.ambient = 0.3;
  plain.diffuse = 0.5;
  SceneAppearance lit = plain;
  lit.lighting.emplace();  // no zones, nothing casts a shadow
  const GrayImage a = RenderDown(world, plain, 1.0, 4.0), b = RenderDown(world, lit, 1.0, 4.0);
  const double worst = WorstDifference(a, b, 1.0, [](int) { return true; });
  std::printf("unlit against lit program: at most %.0f grey levels apart\n", worst);
  EXPECT_LE(worst, 1.0);
}

// A zone of gain 0.5 over x < 4 under the camera (its border on the image's middle
// column), and the exposure: each scales the grey levels it covers.
TEST(SceneLightingTest, AZonesGainAndTheExposureScaleTheGreyLevels) {
  const sim::World world = test::FlatWorld({});
  SceneAppearance lit = test::AmbientOnly();
  lit.ambient = 0.9;
  lit.lighting.emplace();
  const GrayImage base = RenderDown(world, lit, 1.0, 4.0);
  LightZone shade;
  shade.center_m = {0, 0};
  shade.size_m = {8, 20};  // x in [−4, 4]
  shade.gain = 0.5;
  shade.edge_m = 0.2;
  lit.lighting->zones.push_back(shade);
  const GrayImage shaded = RenderDown(world, lit, 1.0, 4.0);
  // 3 m away a 160-px, 60° image spans 3.46 m: 46 px a metre; the edge is ±0.1 m.
  const double inside = WorstDifference(shaded, base, 0.5, [](int u) { return u < 72; });
  const double outside = WorstDifference(shaded, base, 1.0, [](int u) { return u > 88; });
  // Four times the light, exposed for a quarter: the base image, though four times
  // its light would clip at exposure 1 (the render is exposed before its output clips).
  shade.gain = 4.0;
  shade.size_m = {40, 40};
  lit.lighting->zones = {shade};
  const GrayImage bright = RenderDown(world, lit, 1.0, 4.0);
  const GrayImage exposed = RenderDown(world, lit, 0.25, 4.0);
  const double quarter = WorstDifference(exposed, base, 1.0, [](int) { return true; });
  int clipped = 0;
  for (const std::uint8_t p : bright.pixels) clipped += (p == 255);
  std::printf(
      "in the zone %.2f, beyond it %.2f, 4x the light exposed at 1/4 %.2f grey levels off "
      "(%d pixels clip at exposure 1)\n",
      inside, outside, quarter, clipped);
  EXPECT_LE(inside, 1.0);
  EXPECT_LE(outside, 1.0);
  EXPECT_GT(clipped, static_cast<int>(bright.pixels.size() / 2));
  EXPECT_LE(quarter, 1.0);
}

// In a post's shadow only the sun's light is gone: the ground there is ambient / (ambient
// + diffuse · sin elevation) as bright as without the shadow.
TEST(SceneLightingTest, AShadowTakesTheSunsLightAndLeavesTheSkys) {
  // Out of the camera's view, 2 m off its axis.
  sim::StaticObject post = Post({4, 2}, 0.3, 6.0, "post");
  const sim::World world = test::FlatWorld({post});
  SceneAppearance lit;
  lit.sun_azimuth_deg = 90.0;  // from +y: the shadow falls along −y, under the camera
  lit.sun_elevation_deg = 60.0;
  lit.ambient = 0.3;
  lit.diffuse = 0.5;
  lit.lighting.emplace();
  lit.lighting->sun_shadows = false;
  const GrayImage sunny = RenderDown(world, lit, 1.0, 4.0);
  lit.lighting->sun_shadows = true;
  const GrayImage shaded = RenderDown(world, lit, 1.0, 4.0);
  const double expected = 0.3 / (0.3 + 0.5 * std::sin(M_PI / 3));
  // The shadow's core: within 0.13 m of x = 4 (6 px about the middle column), world y
  // from 1 m to −1 m (rows 20 to 100), where the shadow reaches from y = 1.7 to −1.46.
  double sum_shaded = 0.0, sum_sunny = 0.0;
  for (int v = 20; v < 100; ++v) {
    for (int u = 74; u < 87; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * sunny.width + u;
      sum_shaded += shaded.pixels[i];
      sum_sunny += sunny.pixels[i];
    }
  }
  std::printf("shadow / sun %.3f, expected %.3f\n", sum_shaded / sum_sunny, expected);
  EXPECT_NEAR(sum_shaded / sum_sunny, expected, 0.02);
}

}  // namespace
}  // namespace trackbed::render
