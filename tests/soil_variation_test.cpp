// Uneven soil: seeded fields that are a pure function of the seed and the point,
// bounded by the amplitude, smooth, and uncorrelated beyond their length.
#include "trackbed/sim/soil_variation.h"

#include <cmath>
#include <utility>

#include <gtest/gtest.h>

#include "trackbed/sim/terrain.h"

namespace trackbed::sim {
namespace {

SoilVariationOptions Options(double amplitude, double length_m) {
  SoilVariationOptions o;
  o.amplitude = amplitude;
  o.correlation_length_m = length_m;
  return o;
}

TEST(SoilVariationTest, OffLeavesTheMaterialUnchanged) {
  const SoilPoint base = SoilOf(BuiltinMaterial("sandy_loam"));
  const SoilVariation off(Options(0.0, 2.0), 7);
  const SoilPoint s = off.Apply(base, 3.3, -1.2);
  EXPECT_EQ(s.cohesion_pa, base.cohesion_pa);
  EXPECT_EQ(s.tan_phi, base.tan_phi);
  EXPECT_EQ(s.shear_modulus_m, base.shear_modulus_m);
  EXPECT_EQ(s.bekker_kphi, base.bekker_kphi);
}

TEST(SoilVariationTest, ValuesAreAPureFunctionOfSeedAndPoint) {
  const SoilVariation a(Options(0.3, 2.0), 11), again(Options(0.3, 2.0), 11);
  const SoilVariation other(Options(0.3, 2.0), 12);
  int differ = 0;
  for (int k = 0; k < 50; ++k) {
    const double x = -40.0 + 1.7 * k, y = 13.0 - 0.9 * k;
    for (auto f : {SoilVariation::kCohesion, SoilVariation::kTanPhi, SoilVariation::kKphi}) {
      EXPECT_EQ(a.Value(f, x, y), again.Value(f, x, y));
      differ += a.Value(f, x, y) != other.Value(f, x, y);
    }
  }
  EXPECT_GT(differ, 140);
  // Far from the origin too (a later tile of a large world): same rule.
  EXPECT_EQ(a.Value(SoilVariation::kKc, 9500.25, -8700.5),
            again.Value(SoilVariation::kKc, 9500.25, -8700.5));
}

TEST(SoilVariationTest, ScaledParametersStayWithinTheAmplitude) {
  const SoilPoint base = SoilOf(BuiltinMaterial("clay"));
  const SoilVariation v(Options(0.25, 1.5), 3);
  double lo = 2.0, hi = 0.0;
  for (int i = 0; i < 200; ++i) {
    for (int j = 0; j < 20; ++j) {
      const SoilPoint s = v.Apply(base, 0.37 * i, 0.41 * j);
      for (double r : {s.cohesion_pa / base.cohesion_pa, s.tan_phi / base.tan_phi,
                       s.shear_modulus_m / base.shear_modulus_m,
                       s.lateral_shear_modulus_m / base.lateral_shear_modulus_m,
                       s.bekker_kc / base.bekker_kc, s.bekker_kphi / base.bekker_kphi}) {
        lo = std::min(lo, r);
        hi = std::max(hi, r);
      }
      EXPECT_EQ(s.bekker_n, base.bekker_n);
    }
  }
  EXPECT_GE(lo, 0.75);
  EXPECT_LE(hi, 1.25);
  EXPECT_LT(lo, 0.85);  // the field uses its range
  EXPECT_GT(hi, 1.15);
  // Rigid ground does not vary.
  const SoilPoint floor = SoilOf(BuiltinMaterial("hard_floor"));
  EXPECT_EQ(v.Apply(floor, 1.0, 2.0).tan_phi, floor.tan_phi);
  EXPECT_TRUE(v.Apply(floor, 1.0, 2.0).IsRigid());
}

TEST(SoilVariationTest, FieldIsSmoothAndDecorrelatesBeyondItsLength) {
  const double length = 2.0;
  const SoilVariation v(Options(0.5, length), 5);
  // Continuity, also across the lattice lines (x or y a multiple of the length,
  // negative ones included): a micrometre apart, nearly equal.
  for (int k = -50; k < 50; ++k) {
    for (const auto& [x, y] : {std::pair{length * k, 0.37 * k}, std::pair{0.29 * k, length * k},
                               std::pair{0.313 * k, -0.77 * k}}) {
      EXPECT_NEAR(v.Value(SoilVariation::kCohesion, x - 1e-6, y),
                  v.Value(SoilVariation::kCohesion, x + 1e-6, y), 1e-5);
      EXPECT_NEAR(v.Value(SoilVariation::kCohesion, x, y - 1e-6),
                  v.Value(SoilVariation::kCohesion, x, y + 1e-6), 1e-5);
    }
  }
  // Correlation of pairs a tenth of a length apart against pairs three lengths apart.
  auto correlation = [&](double dx) {
    double sxy = 0.0, sxx = 0.0, syy = 0.0;
    for (int i = 0; i < 400; ++i) {
      for (int j = 0; j < 10; ++j) {
        const double x = 0.731 * i, y = 5.3 * j;
        const double a = v.Value(SoilVariation::kTanPhi, x, y);
        const double b = v.Value(SoilVariation::kTanPhi, x + dx, y);
        sxy += a * b;
        sxx += a * a;
        syy += b * b;
      }
    }
    return sxy / std::sqrt(sxx * syy);
  };
  EXPECT_GT(correlation(0.1 * length), 0.9);
  EXPECT_LT(std::abs(correlation(3.0 * length)), 0.15);
}

TEST(SoilVariationTest, TerrainSoilFollowsItsSeed) {
  TerrainOptions o;
  o.default_material = "grass";
  o.soil_variation = Options(0.3, 2.0);
  const Terrain a(o, 1), b(o, 2), a2(o, 1);
  const double x = 1.3, y = -2.2;
  const SoilPoint sa = a.SoilAt(a.MaterialAt(x, y), x, y);
  EXPECT_EQ(sa.tan_phi, a2.SoilAt(a2.MaterialAt(x, y), x, y).tan_phi);
  EXPECT_NE(sa.tan_phi, b.SoilAt(b.MaterialAt(x, y), x, y).tan_phi);
  EXPECT_NE(sa.bekker_kphi, b.SoilAt(b.MaterialAt(x, y), x, y).bekker_kphi);
  o.soil_variation.amplitude = 0.0;
  const Terrain flat(o, 1);
  EXPECT_EQ(flat.SoilAt(flat.MaterialAt(x, y), x, y).tan_phi,
            SoilOf(BuiltinMaterial("grass")).tan_phi);
}

TEST(SoilVariationTest, BadOptionsAreRejectedByName) {
  TerrainOptions o;
  o.soil_variation.amplitude = 1.5;
  try {
    Terrain t(o, 1);
    FAIL() << "accepted amplitude 1.5";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("soil_variation.amplitude"), std::string::npos)
        << e.what();
  }
  o.soil_variation = Options(0.2, 0.0);
  EXPECT_THROW(Terrain(o, 1), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::sim
