// The ground tiled stochastically as the renderer draws it: seen from straight above,
// a classic-look ground repeats exactly at its tile's pitch and a detailed-look one does
// not; listing a material in `classic_look_materials` draws it byte for byte as the
// classic look; and the same scene and seed draw the same bytes.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "trackbed/common/option_error.h"
#include "trackbed/render/renderer.h"
#include "trackbed/robot/stereo_rig.h"

namespace trackbed::render {
namespace {

constexpr int kPitchPx = 96;  // one 1 m tile in pixels, straight down from K.fx / 96 m

sim::World Ground(const std::string& material) {
  sim::TerrainOptions t;
  t.extent_m = {-10, -10, 10, 10};
  t.cell_size_m = 0.5;
  t.default_material = material;
  return sim::World(sim::WorldOptions{}, sim::Terrain(t, 1), {});
}

// Straight down from `height` m over (0.3, 0.2) (OpenCV axes: x along world x, y along −y).
Eigen::Isometry3d LookingDown(double height) {
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d(1, 0, 0);
  R.col(1) = Eigen::Vector3d(0, -1, 0);
  R.col(2) = Eigen::Vector3d(0, 0, -1);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = Eigen::Vector3d(0.3, 0.2, height);
  return T;
}

GrayImage Draw(const std::string& material, const SceneAppearance& a, std::uint64_t seed = 1) {
  const sim::World world = Ground(material);
  const geometry::PinholeCamera K = robot::StereoRig(robot::StereoRigOptions{}).intrinsics();
  Renderer r(world, a, {}, seed, K.width_px, K.height_px, 0.05, 120.0);
  GrayImage img;
  r.Render(K, LookingDown(K.fx / kPitchPx), 0.0, &img, nullptr);
  return img;
}

// The correlation coefficient of the image with itself shifted `dx` columns.
double Correlation(const GrayImage& img, int dx) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  int n = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x + dx < img.width; ++x) {
      const double a = img.pixels[static_cast<std::size_t>(y * img.width + x)];
      const double b = img.pixels[static_cast<std::size_t>(y * img.width + x + dx)];
      sa += a;
      sb += b;
      saa += a * a;
      sbb += b * b;
      sab += a * b;
      ++n;
    }
  }
  const double cov = sab / n - (sa / n) * (sb / n);
  return cov / std::sqrt((saa / n - (sa / n) * (sa / n)) * (sbb / n - (sb / n) * (sb / n)));
}

SceneAppearance Look(GroundLook look) {
  SceneAppearance a = test::AmbientOnly();
  a.ground_look = look;
  return a;
}

// The tile's pitch: 1 classic, under 0.2 detailed for every ground material (the
// correlation within a pixel or two, 0.3–0.9, says there is detail to correlate).
TEST(GroundTilingRenderTest, DetailedGroundHasNoPeriodAtTheTilePitch) {
  for (const std::string material : {"asphalt", "grass", "sandy_loam", "dry_sand"}) {
    const GrayImage classic = Draw(material, Look(GroundLook::kClassic));
    const GrayImage detailed = Draw(material, Look(GroundLook::kDetailed));
    std::printf("%s: classic %.3f detailed %.3f (1 px: %.3f)\n", material.c_str(),
                Correlation(classic, kPitchPx), Correlation(detailed, kPitchPx),
                Correlation(detailed, 1));
    EXPECT_GT(Correlation(classic, kPitchPx), 0.99) << material;
    EXPECT_LT(Correlation(detailed, kPitchPx), 0.2) << material;
    EXPECT_GT(Correlation(detailed, 1), 0.3) << material;
  }
}

// The detailed recipes' own 0.5 m tiles (ground_sand.h, ground_grass.h, ground_soil.h):
// no period at that pitch either. The dry sand's variants share their edges (their
// ripples continue across them), so its tiles correlate more, within the same bound.
TEST(GroundTilingRenderTest, DetailedRecipesHaveNoPeriodAtTheirOwnTile) {
  for (const std::string material : {"grass", "sandy_loam", "dry_sand"}) {
    const GrayImage detailed = Draw(material, Look(GroundLook::kDetailed));
    std::printf("%s: detailed at 0.5 m %.3f\n", material.c_str(),
                Correlation(detailed, kPitchPx / 2));
    EXPECT_LT(Correlation(detailed, kPitchPx / 2), 0.2) << material;
  }
}

TEST(GroundTilingRenderTest, ClassicListedMaterialDrawsAsTheClassicLook) {
  SceneAppearance listed = Look(GroundLook::kDetailed);
  listed.classic_look_materials = {"grass"};
  EXPECT_EQ(Draw("grass", listed).pixels, Draw("grass", Look(GroundLook::kClassic)).pixels);
  EXPECT_NE(Draw("grass", Look(GroundLook::kDetailed)).pixels,
            Draw("grass", Look(GroundLook::kClassic)).pixels);
}

TEST(GroundTilingRenderTest, SameSeedSameBytesOtherSeedOtherTiles) {
  const SceneAppearance a = Look(GroundLook::kDetailed);
  EXPECT_EQ(Draw("asphalt", a, 4).pixels, Draw("asphalt", a, 4).pixels);
  EXPECT_NE(Draw("asphalt", a, 4).pixels, Draw("asphalt", a, 5).pixels);
}

TEST(GroundTilingRenderTest, ClassicLooksUnknownMaterialIsRejected) {
  SceneAppearance a;
  a.classic_look_materials = {"cobblestone"};
  EXPECT_THROW(a.Validate(), OptionError);
}

}  // namespace
}  // namespace trackbed::render
