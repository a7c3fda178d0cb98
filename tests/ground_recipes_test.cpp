// The detailed look's recipes of the robot's ground materials (render/ground_sand.h,
// ground_grass.h, ground_soil.h), on the CPU: the bytes repeat and are pinned, variants
// differ, the dry sand's variants agree at their edges, and what the recipes state of
// the surfaces they model holds of the textures: the ripples' wavelength read from the
// texture's spectrum, the ripple index, the blades' widths and counts, the cracks' share.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "ground_grass.h"
#include "ground_sand.h"
#include "ground_soil.h"
#include "texel_checksum.h"
#include "texture_blocks.h"
#include "trackbed/render/procedural_texture.h"

namespace trackbed::render {
namespace {

constexpr double kPi = 3.14159265358979323846;
const char* const kDetailed[] = {"dry_sand", "grass", "sandy_loam"};

// The seed a recipe receives from MakeTextureVariants' `seed`.
std::uint64_t RecipeSeed(const std::string& name, std::uint64_t seed) {
  return texture_blocks::Mix(seed ^ texture_blocks::HashName(name));
}

TEST(GroundRecipesTest, SameSeedSameBytesOtherSeedOtherBytes) {
  for (const std::string name : kDetailed) {
    const std::vector<Texture> a = MakeTextureVariants(name, 5);
    const std::vector<Texture> b = MakeTextureVariants(name, 5);
    const std::vector<Texture> c = MakeTextureVariants(name, 6);
    ASSERT_EQ(a.size(), 4u) << name;
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].texels, b[k].texels) << name << " " << k;
      EXPECT_NE(a[k].texels, c[k].texels) << name << " " << k;
      EXPECT_EQ(a[k].meters_per_repeat, 0.5) << name;
    }
    // The classic texture is not the detailed look's.
    EXPECT_NE(MakeTexture(name, 5).texels, a[0].texels) << name;
    EXPECT_EQ(MakeTexture(name, 5).meters_per_repeat, 1.0) << name;
  }
}

// The bytes for one seed, pinned (as ProceduralTextureTest's): update only for a
// deliberate change of a recipe.
TEST(GroundRecipesTest, BytesMatchPinnedChecksums) {
  const std::uint64_t pinned[][2] = {
      {0x716fee6313360a85ULL, 0x163023d70b346735ULL},  // dry_sand: variants 0 and 3
      {0x2dcb12199d49708bULL, 0x8b4cf3772374f09cULL},  // grass
      {0x1406375ac506672eULL, 0xa0a66d07a8dabb6eULL},  // sandy_loam
  };
  for (int m = 0; m < 3; ++m) {
    const std::vector<Texture> v = MakeTextureVariants(kDetailed[m], 42, 64);
    EXPECT_EQ(test::TexelChecksum(v[0]), pinned[m][0]) << kDetailed[m];
    EXPECT_EQ(test::TexelChecksum(v[3]), pinned[m][1]) << kDetailed[m];
  }
}

// Every pair of variants differs: over a fifth of the texels for grass and soil (each
// variant its own ground), over a twentieth for the sand (its ripples shared at the edges).
TEST(GroundRecipesTest, VariantsDiffer) {
  for (const std::string name : kDetailed) {
    const std::vector<Texture> v = MakeTextureVariants(name, 9);
    const double bound = name == "dry_sand" ? 0.05 : 0.2;
    for (std::size_t i = 0; i < v.size(); ++i) {
      for (std::size_t j = i + 1; j < v.size(); ++j) {
        int differ = 0;
        for (std::size_t t = 0; t < v[i].texels.size(); ++t) {
          differ += std::abs(v[i].texels[t] - v[j].texels[t]) > 2 ? 1 : 0;
        }
        EXPECT_GT(differ, bound * static_cast<double>(v[i].texels.size()))
            << name << " " << i << " " << j;
      }
    }
  }
}

// The dry sand's variants are the same bytes within 4 texels (8 mm) of the tile's edges
// and each wraps seamlessly, so that tiles of any variants meet without a step where
// their shifts agree; its tiling takes no turn or mirror (the wind's direction) and any
// shift (docs/rendering.md: no shift would leave a period).
TEST(GroundRecipesTest, SandVariantsAgreeAtTheirEdges) {
  constexpr int kSize = 256;
  const std::vector<Texture> v = MakeTextureVariants("dry_sand", 3, kSize);
  for (std::size_t k = 1; k < v.size(); ++k) {
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const int edge = std::min(std::min(x, kSize - 1 - x), std::min(y, kSize - 1 - y));
        if (edge < 4) {
          ASSERT_EQ(v[k].at(x, y), v[0].at(x, y)) << k << " " << x << " " << y;
        }
      }
    }
  }
  const TileVariation t = GroundTileVariation("dry_sand");
  EXPECT_EQ(t.quarter_turns, 1);
  EXPECT_FALSE(t.mirror);
  EXPECT_EQ(t.offsets_per_side, 0);
  EXPECT_EQ(t.variants, kSandVariants);
  // Across the wrap (column 255 to 0) the texels step as much as within the tile.
  double across = 0.0, within = 0.0;
  for (int y = 0; y < kSize; ++y) {
    across += std::abs(v[0].at(0, y) - v[0].at(kSize - 1, y));
    within += std::abs(v[0].at(kSize / 2, y) - v[0].at(kSize / 2 - 1, y));
  }
  EXPECT_LT(across, 1.5 * within);
}

// Over 40 seeds the ripples' wavelength and index lie in the ranges the recipe cites.
TEST(GroundRecipesTest, RippleWavelengthAndIndexWithinTheCitedRanges) {
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const RippleField r = SandRipples(seed);
    EXPECT_GE(r.wavelength_m, kRippleWavelengthMinM);
    EXPECT_LE(r.wavelength_m, kRippleWavelengthMaxM);
    EXPECT_GE(r.wavelength_m / r.height_m, kRippleIndexMin);
    EXPECT_LE(r.wavelength_m / r.height_m, kRippleIndexMax);
  }
}

// The texture's spectrum peaks at the ripples' wave vector: its wavelength, read from the
// bytes, within the cited 6–12.5 cm, and the one the recipe drew.
TEST(GroundRecipesTest, RippleWavelengthFromTheTexturesSpectrum) {
  constexpr int kSize = 256;
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const Texture t = MakeTextureVariants("dry_sand", seed, kSize)[1];
    double mean = 0.0;
    for (const std::uint8_t b : t.texels) mean += b;
    mean /= static_cast<double>(t.texels.size());
    // cos and sin of j·π/kSize: every angle below is a multiple of it.
    std::vector<double> cosine(2 * kSize), sine(2 * kSize);
    for (int j = 0; j < 2 * kSize; ++j) {
      cosine[j] = std::cos(kPi * j / kSize);
      sine[j] = std::sin(kPi * j / kSize);
    }
    double best = -1.0;
    int best_kx = 0, best_ky = 0;
    for (int ky = 1; ky <= 20; ++ky) {
      for (int kx = -10; kx <= 10; ++kx) {
        double re = 0.0, im = 0.0;
        for (int y = 0; y < kSize; ++y) {
          for (int x = 0; x < kSize; ++x) {
            const int j =
                ((2 * (kx * x + ky * y) + kx + ky) % (2 * kSize) + 2 * kSize) % (2 * kSize);
            const double g = t.at(x, y) - mean;
            re += g * cosine[j];
            im += g * sine[j];
          }
        }
        const double power = re * re + im * im;
        if (power > best) {
          best = power;
          best_kx = kx;
          best_ky = ky;
        }
      }
    }
    const double wavelength = kSandTileM / std::sqrt(best_kx * best_kx + best_ky * best_ky);
    EXPECT_GE(wavelength, kRippleWavelengthMinM) << seed;
    EXPECT_LE(wavelength, kRippleWavelengthMaxM) << seed;
    const RippleField r = SandRipples(RecipeSeed("dry_sand", seed));
    EXPECT_NEAR(wavelength, r.wavelength_m, 1e-9) << seed;
  }
}

// The sward: blades 2–4 mm wide, 3–4 per shoot, 150 shoots per dm² of the tile, deeper
// ones first.
TEST(GroundRecipesTest, SwardFollowsTheTurfFigures) {
  const std::vector<GrassBlade> blades = GrassSward(11, 2);
  const double shoots = kShootsPerDm2 * kGrassTileM * kGrassTileM * 100.0;
  EXPECT_GE(blades.size(), static_cast<std::size_t>(kLeavesPerShootMin * shoots));
  EXPECT_LE(blades.size(), static_cast<std::size_t>(kLeavesPerShootMax * shoots));
  for (std::size_t k = 0; k < blades.size(); ++k) {
    EXPECT_GE(blades[k].width_mm, kBladeWidthMinMm);
    EXPECT_LE(blades[k].width_mm, kBladeWidthMaxMm);
    if (k > 0) {
      EXPECT_GE(blades[k].depth, blades[k - 1].depth);
    }
  }
}

// The cracks open some of the ground and less than the largest share measured.
TEST(GroundRecipesTest, CracksCoverUnderTheMeasuredMaximum) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    for (int variant = 0; variant < kSoilVariants; ++variant) {
      const double share = SoilCrackShare(seed, variant, 256);
      EXPECT_GT(share, 0.002) << seed << " " << variant;
      EXPECT_LE(share, kMaxCrackShare) << seed << " " << variant;
    }
  }
}

TEST(GroundRecipesTest, UnknownAppearanceThrowsNamingIt) {
  try {
    MakeTextureVariants("moss", 1);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'moss'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(MakeTextureVariants("grass", 1, 100), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::render
