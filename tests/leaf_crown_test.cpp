// Leafy crowns (render/trackbed/render/leaf_crown.h): the cards from the tree's seed (the
// same seed the same cards, each inside the crown, their leaf area the cited leaf area
// index over the crown's projection, their normals spread over the sphere); the crown as
// the renderer draws it against a 4 x 4 supersampled render (the pixels its leaves cover
// partly drawn by their coverage) and the same bytes twice; the scenario key and its
// errors; the KITTI twin's street furniture where scripts/kitti_twin_scene.py puts it.
#include "trackbed/render/leaf_crown.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render_test_scene.h"
#include "scenario_error_of.h"
#include "trackbed/render/renderer.h"

namespace trackbed::render {
namespace {

std::vector<double> SprayAreas(std::uint64_t seed) {
  std::vector<double> areas;
  for (const LeafSpray& s : MakeLeafSprays(seed, 128)) areas.push_back(s.leaf_area_m2);
  return areas;
}

TEST(LeafCrownTest, SpraysAreTheSameForTheSameSeedAndHoldLeavesOfTheCitedSize) {
  const std::vector<LeafSpray> a = MakeLeafSprays(11, 128), b = MakeLeafSprays(11, 128);
  const std::vector<LeafSpray> c = MakeLeafSprays(12, 128);
  ASSERT_EQ(a.size(), static_cast<std::size_t>(kLeafSprayVariants));
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].grey, b[k].grey);
    EXPECT_EQ(a[k].coverage, b[k].coverage);
    EXPECT_NE(a[k].coverage, c[k].coverage);
    // Three twigs of 10-12 leaves 4 cm apart, each blade 0.69 W L (the profile's
    // integral) with W = 0.9 L and L in 6-10 cm, 0.0022-0.0062 m^2: 0.07-0.22 m^2 before
    // overlaps and the card's edges cut them, 0.28-0.9 of the card.
    const double share = a[k].leaf_area_m2 / (kLeafCardSideM * kLeafCardSideM);
    std::printf("spray %zu: leaf area %.4f m^2, %.2f of the card\n", k, a[k].leaf_area_m2, share);
    EXPECT_GT(share, 0.28);
    EXPECT_LT(share, 0.9);
  }
  EXPECT_THROW(MakeLeafSprays(1, 100), std::invalid_argument);
}

// FNV-1a of the cards' coordinates' bits and variants.
std::uint64_t CardsChecksum(const std::vector<LeafCard>& cards) {
  std::uint64_t h = 14695981039346656037ULL;
  const auto mix = [&h](std::uint64_t b) {
    for (int k = 0; k < 8; ++k) {
      h ^= (b >> (8 * k)) & 0xffU;
      h *= 1099511628211ULL;
    }
  };
  for (const LeafCard& c : cards) {
    for (const Eigen::Vector3d* v : {&c.center, &c.half_u, &c.half_v}) {
      for (int i = 0; i < 3; ++i) {
        std::uint64_t b = 0;
        std::memcpy(&b, &(*v)(i), sizeof b);
        mix(b);
      }
    }
    mix(static_cast<std::uint64_t>(c.variant));
  }
  return h;
}

// A crown's cards for one seed, pinned: the same on every compiler (each coordinate
// drawn in an order the code fixes, not in a constructor's arguments, whose order of
// evaluation C++ leaves to the compiler).
TEST(LeafCrownTest, CardsMatchPinnedChecksum) {
  const std::vector<LeafCard> cards =
      LeafCrownCards(Eigen::Vector3d(2.0, -1.0, 7.0), 2.5, 99, SprayAreas(3));
  EXPECT_EQ(CardsChecksum(cards), 0x8a353c0b50122880ULL);
}

TEST(LeafCrownTest, CardsFromTheSeedLieInsideTheCrownAtTheCitedLeafAreaIndex) {
  const std::vector<double> areas = SprayAreas(3);
  const Eigen::Vector3d center(2.0, -1.0, 7.0);
  const double radius = 2.5;
  const std::vector<LeafCard> cards = LeafCrownCards(center, radius, 99, areas);
  const std::vector<LeafCard> again = LeafCrownCards(center, radius, 99, areas);
  const std::vector<LeafCard> other = LeafCrownCards(center, radius, 100, areas);
  ASSERT_EQ(again.size(), cards.size());
  double area = 0.0, mean_abs_z = 0.0;
  for (std::size_t k = 0; k < cards.size(); ++k) {
    const LeafCard& c = cards[k];
    EXPECT_EQ(c.center, again[k].center);
    EXPECT_EQ(c.half_u, again[k].half_u);
    EXPECT_EQ(c.half_v, again[k].half_v);
    EXPECT_EQ(c.variant, again[k].variant);
    EXPECT_NEAR(c.half_u.dot(c.half_v), 0.0, 1e-12);
    EXPECT_NEAR(2 * c.half_u.norm(), kLeafCardSideM, 1e-12);
    EXPECT_NEAR(2 * c.half_v.norm(), kLeafCardSideM, 1e-12);
    for (double su : {-1.0, 1.0}) {
      for (double sv : {-1.0, 1.0}) {
        EXPECT_LE((c.center + su * c.half_u + sv * c.half_v - center).norm(), radius + 1e-12);
      }
    }
    area += areas[static_cast<std::size_t>(c.variant)];
    mean_abs_z += std::abs(c.Normal().z());
  }
  mean_abs_z /= static_cast<double>(cards.size());
  EXPECT_NE(other.front().center, cards.front().center);
  // The leaf area over the crown's projection: the cited index, within one card's area.
  const double projection = M_PI * radius * radius;
  const double largest = *std::max_element(areas.begin(), areas.end());
  std::printf("%zu cards, leaf area index %.4f, mean |n_z| %.4f\n", cards.size(), area / projection,
              mean_abs_z);
  EXPECT_GE(area / projection, kCrownLeafAreaIndex);
  EXPECT_LT(area / projection, kCrownLeafAreaIndex + largest / projection);
  // Normals uniform over the sphere: |n_z| uniform on [0, 1], mean 1/2 (standard error
  // 0.29 / sqrt(N), under 0.011 for these cards).
  EXPECT_NEAR(mean_abs_z, 0.5, 0.035);
  EXPECT_THROW(LeafCrownCards(center, 0.3, 1, areas), std::invalid_argument);
  EXPECT_THROW(LeafCrownCards(center, radius, 1, {0.01, 0.0}), std::invalid_argument);
  EXPECT_NE(LeafCrownSeed(1, {3.0, 4.0}), LeafCrownSeed(1, {3.0, 4.5}));
  EXPECT_NE(LeafCrownSeed(1, {3.0, 4.0}), LeafCrownSeed(2, {3.0, 4.0}));
}

// A 4 m tree (crown radius 4/3 m about its top) 8 m ahead of a level camera at the
// crown's height, against a black sky, lit by ambient light alone.
sim::World OneTree() {
  sim::StaticObject tree;
  tree.kind = "tree";
  tree.shape = sim::StaticObject::Shape::kCylinder;
  tree.appearance = "bark";
  tree.center_m = {8.0, 0.0};
  tree.base_z_m = 0.0;
  tree.radius_m = 0.15;
  tree.height_m = 4.0;
  return test::FlatWorld({tree}, {-2, -6, 12, 6});
}

GrayImage DrawTree(int scale, CrownLook look) {
  SceneAppearance a = test::AmbientOnly();
  a.tree_crowns = true;
  a.crowns = look;
  const int w = 160 * scale, h = 120 * scale;
  geometry::PinholeCamera K;
  K.width_px = w;
  K.height_px = h;
  K.fx = K.fy = 150.0 * scale;
  K.cx = scale * (79.5 + 0.5) - 0.5;  // the same view, pixel for pixel at scale 1
  K.cy = scale * (59.5 + 0.5) - 0.5;
  const sim::World world = OneTree();  // outlives the renderer, which keeps its terrain
  Renderer renderer(world, a, {}, 5, w, h, 0.05, 100.0);
  GrayImage img;
  renderer.Render(K, test::Looking({0.0, 0.0, 4.0}, Eigen::Vector3d::UnitX()), 0.0, &img, nullptr);
  return img;
}

// The mean of each 4 x 4 block: what a camera's pixel integrates.
std::vector<double> BoxDown4(const GrayImage& fine) {
  const int w = fine.width / 4, h = fine.height / 4;
  std::vector<double> out(static_cast<std::size_t>(w) * h, 0.0);
  for (int v = 0; v < fine.height; ++v) {
    for (int u = 0; u < fine.width; ++u) {
      out[static_cast<std::size_t>(v / 4) * w + u / 4] += fine.at(u, v) / 16.0;
    }
  }
  return out;
}

TEST(LeafCrownRenderTest, SilhouettePixelsTakeTheirCoverageAsASupersampledRenderAndRepeat) {
  const GrayImage img = DrawTree(1, CrownLook::kLeaves);
  const GrayImage twice = DrawTree(1, CrownLook::kLeaves);
  EXPECT_EQ(img.pixels, twice.pixels);
  const std::vector<double> ref = BoxDown4(DrawTree(4, CrownLook::kLeaves));
  // The crown's outline: 150 px x (4/3 m) / 8 m = 25 px about (79.5, 59.5). Its outer
  // ring (0.7 to 1.1 of that radius), where the sky shows between the leaves.
  double sum = 0.0, sum_ref = 0.0, sq = 0.0;
  int n = 0, partial = 0, partial_ref = 0;
  for (int v = 0; v < img.height; ++v) {
    for (int u = 0; u < img.width; ++u) {
      const double r = std::hypot(u - 79.5, v - 59.5) / 25.0;
      if (r < 0.7 || r > 1.1 || v > 59) continue;  // the upper half: no trunk
      const double g = img.at(u, v), g_ref = ref[static_cast<std::size_t>(v) * img.width + u];
      sum += g;
      sum_ref += g_ref;
      sq += (g - g_ref) * (g - g_ref);
      ++n;
      partial += g > 0 && g < 39;  // a leaf's tone is 39 and more: partly covered
      partial_ref += g_ref > 0.5 && g_ref < 39;
    }
  }
  ASSERT_GT(n, 500);
  const double rms = std::sqrt(sq / n);
  std::printf("ring: mean %.2f (reference %.2f), RMS difference %.2f, partly covered %d (%d)\n",
              sum / n, sum_ref / n, rms, partial, partial_ref);
  EXPECT_GT(sum_ref / n, 10.0);  // the ring holds leaves and sky
  EXPECT_NEAR(sum / n, sum_ref / n, 0.08 * sum_ref / n);
  // Alpha-tested leaves would leave none partly covered; blending by coverage leaves
  // 16 against the reference's 49 here (where cards overlap, their fringes add up).
  EXPECT_GT(partial, partial_ref / 4);
  EXPECT_LT(rms, 15.0);
}

TEST(LeafCrownRenderTest, SpheresStayTheDefault) {
  EXPECT_EQ(SceneAppearance{}.crowns, CrownLook::kSpheres);
  EXPECT_NE(DrawTree(1, CrownLook::kSpheres).pixels, DrawTree(1, CrownLook::kLeaves).pixels);
}

using scenario::test::ErrorOf;

TEST(LeafCrownScenarioTest, TheKeyReadsLeavesAndSpheresAndNamesFileKeyAndValueOtherwise) {
  const std::string drive = "drive:\n  waypoints: [[0, 0], [5, 0]]\n";
  EXPECT_EQ(scenario::ParseScenario(drive + "scene: {appearance: {crowns: leaves}}\n", "a.yaml")
                .scene.appearance.crowns,
            CrownLook::kLeaves);
  EXPECT_EQ(scenario::ParseScenario(drive, "a.yaml").scene.appearance.crowns, CrownLook::kSpheres);
  const std::string error = ErrorOf(drive + "scene: {appearance: {crowns: needles}}\n");
  std::printf("%s\n", error.c_str());
  EXPECT_NE(error.find("test.yaml"), std::string::npos) << error;
  EXPECT_NE(error.find("scene.appearance.crowns"), std::string::npos) << error;
  EXPECT_NE(error.find("needles"), std::string::npos) << error;
  EXPECT_NE(ErrorOf(drive + "scene: {appearance: {crowns: [leaves]}}\n"), "");
}

TEST(KittiTwinFurnitureTest, KerbsLineTheCarriagewayAndLampsAndSignsStandClearOfTheLanes) {
  const scenario::Scenario s =
      scenario::LoadScenario(std::string(TRACKBED_SOURCE_DIR) + "/scenes/kitti_twin.yaml");
  EXPECT_EQ(s.scene.appearance.crowns, CrownLook::kLeaves);
  std::vector<double> kerb_x[2];
  int lamps = 0, signs = 0;
  for (const sim::StaticObject& o : s.scene.objects) {
    const double y = std::abs(o.center_m.y());
    if (o.kind == "box" && o.appearance == "paving") {  // a kerbstone: DIN 483 H 15 x 30
      EXPECT_NEAR(y - 0.075, 4.0, 1e-9);                // its face on the carriageway's edge
      EXPECT_NEAR(o.size_m.x(), 0.995, 1e-9);
      EXPECT_NEAR(o.size_m.y(), 0.15, 1e-9);
      EXPECT_NEAR(o.size_m.z(), 0.12, 1e-9);
      kerb_x[o.center_m.y() > 0].push_back(o.center_m.x());
    } else if (o.kind == "post" && o.radius_m == 0.07) {  // a street lamp, behind the footway
      ++lamps;
      EXPECT_NEAR(o.height_m, 6.0, 1e-9);
      EXPECT_NEAR(y, 8.5, 1e-9);
    } else if (o.kind == "post" && o.radius_m < 0.04) {  // a sign post: 60.3 mm tube
      ++signs;
      EXPECT_NEAR(o.height_m, 2.6, 1e-9);  // the sign's lower edge at 2 m
      EXPECT_GE(y - 0.3, 4.5 - 1e-9);      // the sign 0.5 m off the carriageway
    }
    // Nothing of the furniture on the carriageway, where the lanes are driven.
    if ((o.kind == "post" && o.radius_m < 0.08) || o.appearance == "paving") {
      EXPECT_GE(y - (o.kind == "post" ? o.radius_m : o.size_m.y() / 2), 4.0 - 1e-9);
    }
  }
  // The kerbs run the street's length without gaps: one stone a metre.
  for (std::vector<double>& xs : kerb_x) {
    ASSERT_GT(xs.size(), 600u);
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 1; k < xs.size(); ++k) EXPECT_NEAR(xs[k] - xs[k - 1], 1.0, 1e-6);
    EXPECT_LE(xs.front(), -30.0);
    EXPECT_GE(xs.back(), 640.0);
  }
  EXPECT_GT(lamps, 15);  // every 25-35 m along 670 m
  EXPECT_GT(signs, 10);
}

}  // namespace
}  // namespace trackbed::render
