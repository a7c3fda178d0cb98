// Terramechanics formulas: invariants of the Janosi–Hanamoto and Bekker laws.
#include "trackbed/robot/terramechanics.h"

#include <cmath>

#include <gtest/gtest.h>

namespace trackbed::robot {
namespace {

TEST(TerramechanicsTest, JanosiHanamotoReachesOneMinusInverseEAtK) {
  const sim::TerrainMaterial& sand = sim::BuiltinMaterial("lete_sand");
  EXPECT_DOUBLE_EQ(JanosiHanamotoFraction(sand, 0.0), 0.0);
  EXPECT_NEAR(JanosiHanamotoFraction(sand, sand.shear_modulus_m), 1.0 - std::exp(-1.0), 1e-15);
  EXPECT_NEAR(JanosiHanamotoFraction(sand, 1.0), 1.0, 1e-12);
  // Monotonic and symmetric in the sign of j.
  double last = 0.0;
  for (double j = 1e-4; j < 0.2; j *= 1.5) {
    const double f = JanosiHanamotoFraction(sand, j);
    EXPECT_GT(f, last);
    EXPECT_DOUBLE_EQ(f, JanosiHanamotoFraction(sand, -j));
    last = f;
  }
}

TEST(TerramechanicsTest, ShearStrengthIsMohrCoulomb) {
  const sim::TerrainMaterial& sand = sim::BuiltinMaterial("lete_sand");
  const double area = 0.01, load = 100.0;
  EXPECT_NEAR(ShearStrength(sand, load, area), 1300.0 * area + load * std::tan(31.1 * M_PI / 180.0),
              1e-12);
  const sim::TerrainMaterial& floor = sim::BuiltinMaterial("hard_floor");
  EXPECT_NEAR(ShearStrength(floor, load, area), 0.8 * load, 1e-12);  // μ = 0.8
  EXPECT_DOUBLE_EQ(ShearStrength(floor, -5.0, area), 0.0);           // no tension
}

TEST(TerramechanicsTest, BekkerSinkageInvertsThePressureSinkageLaw) {
  const double b = 0.1;
  for (const char* name : {"lete_sand", "dry_sand", "sandy_loam", "clay", "grass"}) {
    const sim::TerrainMaterial& m = sim::BuiltinMaterial(name);
    for (double p : {1e3, 4e3, 2e4}) {
      const double z = BekkerSinkage(m, p, b);
      EXPECT_GT(z, 0.0) << name;
      EXPECT_NEAR((m.bekker_kc / b + m.bekker_kphi) * std::pow(z, m.bekker_n), p, 1e-9 * p) << name;
    }
  }
  EXPECT_EQ(BekkerSinkage(sim::BuiltinMaterial("hard_floor"), 1e4, b), 0.0);
}

TEST(TerramechanicsTest, CompactionResistanceIsTheWorkOfMakingTheRut) {
  // R = ∫0^z b p(z') dz' = b k z^(n+1)/(n+1): check against a numeric integral.
  const sim::TerrainMaterial& m = sim::BuiltinMaterial("dry_sand");
  const double b = 0.1, z = 0.01, k = m.bekker_kc / b + m.bekker_kphi;
  double integral = 0.0;
  const int steps = 100000;
  for (int i = 0; i < steps; ++i) {
    const double zi = (i + 0.5) * z / steps;
    integral += b * k * std::pow(zi, m.bekker_n) * z / steps;
  }
  EXPECT_NEAR(CompactionResistance(m, z, b), integral, 1e-6 * integral);
  EXPECT_EQ(CompactionResistance(sim::BuiltinMaterial("paving"), z, b), 0.0);
}

TEST(TerramechanicsTest, BuiltinMaterialsAreValidAndNamed) {
  for (const sim::TerrainMaterial& m : sim::BuiltinMaterials()) {
    EXPECT_NO_THROW(m.Validate()) << m.name;
  }
  EXPECT_THROW(sim::BuiltinMaterial("marshmallow"), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::robot
