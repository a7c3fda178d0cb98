// The asphalt texture and the ground's stochastic tiling, on the CPU: the aggregate
// follows the grading it states (render/ground_asphalt.h), the variants share their
// quarters' edges and differ inside, the bytes repeat, and tiles choose their variant,
// turn, mirror and shift evenly from the seed (render/ground_tiling.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "texel_checksum.h"

#include "ground_asphalt.h"
#include "ground_tiling.h"
#include "trackbed/render/procedural_texture.h"

namespace trackbed::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The mix's aggregate volume from its masses: (0.934 / 2.65) · 0.97 / (0.934 / 2.65 +
// 0.066 / 1.03).
TEST(GroundAsphaltTest, AggregateVolumeShareFollowsTheMix) {
  EXPECT_NEAR(AggregateVolumeShare(), 0.82078, 1e-5);
}

// The classes are the SMA 11 S envelope's midpoints: mass passing 2 mm 25 %, 5.6 mm 40 %,
// 8 mm 57.5 %, 11.2 mm 95 %, 16 mm 100 %, each inside TL Asphalt-StB 07/13's limits.
TEST(GroundAsphaltTest, ClassesLieWithinTheSma11Envelope) {
  const double lo[] = {20.0, 35.0, 50.0, 90.0};  // passing 2, 5.6, 8, 11.2 mm [%]
  const double hi[] = {30.0, 45.0, 65.0, 100.0};
  double passing = 25.0;  // below 2 mm
  for (int k = 0; k < 4; ++k) {
    EXPECT_GE(passing, lo[k]) << k;
    EXPECT_LE(passing, hi[k]) << k;
    passing += 100.0 * kSma11Coarse[k].mass_share;
  }
  EXPECT_NEAR(passing, 100.0, 1e-9);
}

// Delesse: each class's faces cover its share of the volume, within 1 % (whole chips).
TEST(GroundAsphaltTest, ChipFacesCoverEachClassesVolumeShare) {
  const std::vector<AggregateChip> chips = AsphaltAggregate(7);
  std::vector<double> area(std::size(kSma11Coarse), 0.0);
  for (const AggregateChip& c : chips) {
    const SieveClass& sc = kSma11Coarse[c.sieve_class];
    EXPECT_GE(c.diameter_mm, sc.lo_mm);
    EXPECT_LT(c.diameter_mm, sc.hi_mm);
    EXPECT_GE(c.aspect, 0.6);
    EXPECT_LE(c.aspect, 1.0);
    area[static_cast<std::size_t>(c.sieve_class)] +=
        0.25 * kPi * c.diameter_mm * c.diameter_mm * c.aspect * 1e-6;
  }
  for (std::size_t k = 0; k < area.size(); ++k) {
    const double expected = AggregateVolumeShare() * kSma11Coarse[k].mass_share;
    EXPECT_NEAR(area[k] / expected, 1.0, 0.05) << "class " << k;
  }
  // Smallest class first, so that larger chips are painted over smaller ones.
  EXPECT_TRUE(std::is_sorted(chips.begin(), chips.end(), [](const auto& a, const auto& b) {
    return a.sieve_class < b.sieve_class;
  }));
}

// The grading as the texture shows it: at 1024 texels a metre (about 1 mm), the bright
// texels (stone, not binder) lie in chips of the stated sizes: the texture's share of
// stone is within the share the faces can show once they overlap.
TEST(GroundAsphaltTest, TextureShowsTheChipsStone) {
  const Texture t = MakeTextureVariants("asphalt", 3, 1024)[0];
  int stone = 0;
  for (const std::uint8_t v : t.texels) stone += v >= 40 ? 1 : 0;  // 0.16 reflectance
  const double share = static_cast<double>(stone) / static_cast<double>(t.texels.size());
  // Faces cover 1 − exp(−Σ areas) of a tile (Poisson placement), clean within 0.5–0.9
  // of their radius (0.25–0.81 of their area).
  const double faces = 1.0 - std::exp(-AggregateVolumeShare() * 0.75);
  EXPECT_GT(share, 0.2 * faces);
  EXPECT_LT(share, 0.81 * faces);
}

// Every variant's bytes for one seed, pinned: the same on every compiler (the rarer
// features draw their sizes one by one, in an order the code fixes, not in a call's
// arguments, whose order of evaluation C++ leaves to the compiler).
TEST(GroundAsphaltTest, VariantBytesMatchPinnedChecksums) {
  const std::vector<std::uint64_t> pinned = {0xa63a469084de09baULL, 0x15720c4ba9c93288ULL,
                                             0xaf1d9a107192afcdULL, 0x96c1774a0990a7ddULL};
  const std::vector<Texture> v = MakeTextureVariants("asphalt", 42, 64);
  ASSERT_EQ(v.size(), pinned.size());
  for (std::size_t k = 0; k < v.size(); ++k) {
    EXPECT_EQ(test::TexelChecksum(v[k]), pinned[k]) << "variant " << k;
  }
}

TEST(GroundAsphaltTest, SameSeedSameBytesOtherSeedOtherBytes) {
  const std::vector<Texture> a = MakeTextureVariants("asphalt", 5, 256);
  const std::vector<Texture> b = MakeTextureVariants("asphalt", 5, 256);
  const std::vector<Texture> c = MakeTextureVariants("asphalt", 6, 256);
  ASSERT_EQ(a.size(), static_cast<std::size_t>(kAsphaltVariants));
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].texels, b[k].texels) << k;
    EXPECT_NE(a[k].texels, c[k].texels) << k;
  }
  EXPECT_EQ(a[0].texels, MakeTexture("asphalt", 5, 256).texels);
}

// Variants share the texels along the quarter lines (u, v = 0 and 1/2), where the
// tiling's half-tile shifts put tile edges, and differ inside: the features.
TEST(GroundAsphaltTest, VariantsShareTheQuarterLinesAndDifferInside) {
  constexpr int kSize = 256;
  const std::vector<Texture> v = MakeTextureVariants("asphalt", 9, kSize);
  for (std::size_t k = 1; k < v.size(); ++k) {
    int differ = 0;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const int dx = std::min(x % (kSize / 2), kSize / 2 - 1 - x % (kSize / 2));
        const int dy = std::min(y % (kSize / 2), kSize / 2 - 1 - y % (kSize / 2));
        const bool on_line = std::min(dx, dy) < 4;  // within 4 texels (1.6 cm)
        const bool same = v[k].at(x, y) == v[0].at(x, y);
        if (on_line) {
          EXPECT_TRUE(same) << "variant " << k << " at " << x << ", " << y;
        }
        differ += same ? 0 : 1;
      }
    }
    EXPECT_GT(differ, kSize * kSize / 100) << "variant " << k;  // a crack, a stain, ...
  }
}

TEST(GroundAsphaltTest, GroundVariationsFollowTheMaterial) {
  EXPECT_EQ(GroundTileVariation("asphalt").variants, kAsphaltVariants);
  EXPECT_EQ(GroundTileVariation("asphalt").offsets_per_side, 2);
  EXPECT_EQ(GroundTileVariation("paving").offsets_per_side, 4);  // whole 0.4 m slabs
  EXPECT_EQ(GroundTileVariation("dry_sand").quarter_turns, 1);   // ripples keep the wind's
  EXPECT_FALSE(GroundTileVariation("dry_sand").mirror);
  EXPECT_EQ(GroundTileVariation("grass").offsets_per_side, 0);
  EXPECT_EQ(GroundTileVariation("bark").variants, 1);  // not a ground: none
  EXPECT_EQ(GroundTileVariation("bark").quarter_turns, 1);
}

// Over 128 × 128 tiles every choice comes up about as often as any other (within 15 %
// of its share), and a tile takes its neighbour's whole choice about as rarely as the
// choices are many (asphalt: 4 turns × 2 × 4 shifts × 4 variants = 128).
TEST(GroundTilingTest, TilesChooseEvenlyAndUnlikeTheirNeighbours) {
  const TileVariation v = GroundTileVariation("asphalt");
  constexpr int kSide = 128;
  std::map<int, int> count;
  int same_as_left = 0;
  auto key = [](const TileChoice& c) {
    return c.quarter_turns + 4 * (c.mirrored ? 1 : 0) +
           8 * static_cast<int>(std::lround(2.0 * c.offset.x())) +
           16 * static_cast<int>(std::lround(2.0 * c.offset.y())) + 32 * c.variant;
  };
  for (int j = -kSide / 2; j < kSide / 2; ++j) {
    for (int i = -kSide / 2; i < kSide / 2; ++i) {
      const TileChoice c = ChooseTile(0x1234abcdU, i, j, v);
      ++count[key(c)];
      same_as_left += key(c) == key(ChooseTile(0x1234abcdU, i - 1, j, v)) ? 1 : 0;
    }
  }
  ASSERT_EQ(count.size(), 128U);
  const double each = kSide * kSide / 128.0;
  for (const auto& [k, n] : count) EXPECT_NEAR(n / each, 1.0, 0.3) << k;
  EXPECT_LT(same_as_left, 3 * kSide * kSide / 128);
  // Free shifts (grass) take any of 1024 positions per side.
  const TileChoice g = ChooseTile(5, 3, 4, GroundTileVariation("grass"));
  EXPECT_GE(g.offset.minCoeff(), 0.0);
  EXPECT_LT(g.offset.maxCoeff(), 1.0);
}

TEST(GroundTilingTest, CoordinatesTurnMirrorAndShiftWithinTheTile) {
  TileChoice c;
  c.quarter_turns = 1;
  c.mirrored = true;
  c.offset = Eigen::Vector2d(0.5, 0.0);
  // (7.25, -2.5): within its tile (0.25, 0.5); mirrored (−0.25, 0.5); turned a quarter
  // counter-clockwise (−0.5, −0.25); shifted (0, −0.25).
  const Eigen::Vector2d st = TiledCoordinates(Eigen::Vector2d(7.25, -2.5), c);
  EXPECT_DOUBLE_EQ(st.x(), 0.0);
  EXPECT_DOUBLE_EQ(st.y(), -0.25);
}

}  // namespace
}  // namespace trackbed::render
