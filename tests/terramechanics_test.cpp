// Terramechanics: invariants of the Janosi–Hanamoto, Bekker, slip-sinkage and
// bulldozing laws, and a track's thrust in steady slip against Wong's closed form.
#include "trackbed/robot/terramechanics.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/robot/track_contact.h"

namespace trackbed::robot {
namespace {

sim::SoilPoint Soil(const char* name) { return sim::SoilOf(sim::BuiltinMaterial(name)); }

TEST(TerramechanicsTest, JanosiHanamotoReachesOneMinusInverseEAtK) {
  const double k = 0.012;
  EXPECT_DOUBLE_EQ(JanosiHanamotoFraction(0.0, k), 0.0);
  EXPECT_NEAR(JanosiHanamotoFraction(k, k), 1.0 - std::exp(-1.0), 1e-15);
  EXPECT_NEAR(JanosiHanamotoFraction(1.0, k), 1.0, 1e-12);
  // Monotonic and symmetric in the sign of j.
  double last = 0.0;
  for (double j = 1e-4; j < 0.2; j *= 1.5) {
    const double f = JanosiHanamotoFraction(j, k);
    EXPECT_GT(f, last);
    EXPECT_DOUBLE_EQ(f, JanosiHanamotoFraction(-j, k));
    last = f;
  }
}

TEST(TerramechanicsTest, ShearStrengthIsMohrCoulomb) {
  const sim::SoilPoint sand = Soil("lete_sand");
  const double area = 0.01, load = 100.0;
  EXPECT_NEAR(ShearStrength(sand, load, area), 1300.0 * area + load * std::tan(31.1 * M_PI / 180.0),
              1e-12);
  const sim::SoilPoint floor = Soil("hard_floor");
  EXPECT_NEAR(ShearStrength(floor, load, area), load * floor.tan_phi, 1e-12);
  EXPECT_DOUBLE_EQ(ShearStrength(floor, -5.0, area), 0.0);  // no tension
}

TEST(TerramechanicsTest, IsotropicPadShearIsTheVectorJanosiHanamotoLaw) {
  sim::SoilPoint s = Soil("lete_sand");
  s.lateral_shear_modulus_m = s.shear_modulus_m;
  s.lateral_strength_ratio = 1.0;
  const double strength = 50.0;
  for (const Eigen::Vector2d& j :
       {Eigen::Vector2d(0.01, 0.0), Eigen::Vector2d(0.003, -0.02), Eigen::Vector2d(-0.05, 0.05)}) {
    const Eigen::Vector2d f = PadShearForce(s, strength, j);
    const Eigen::Vector2d expected =
        -strength * JanosiHanamotoFraction(j.norm(), s.shear_modulus_m) * j / j.norm();
    EXPECT_NEAR((f - expected).norm(), 0.0, 1e-12);
  }
  EXPECT_EQ(PadShearForce(s, strength, Eigen::Vector2d::Zero()), Eigen::Vector2d::Zero());
}

TEST(TerramechanicsTest, AnisotropicPadShearSaturatesOnTheStrengthEllipse) {
  sim::SoilPoint s = Soil("lete_sand");
  s.lateral_shear_modulus_m = 0.5 * s.shear_modulus_m;
  s.lateral_strength_ratio = 0.6;
  const double strength = 80.0;
  // Far displacement along each axis mobilises that axis's strength.
  EXPECT_NEAR(PadShearForce(s, strength, {1.0, 0.0}).x(), -strength, 1e-9);
  EXPECT_NEAR(PadShearForce(s, strength, {0.0, 1.0}).y(), -0.6 * strength, 1e-9);
  // Any far displacement ends on the ellipse (S, r S).
  const Eigen::Vector2d f = PadShearForce(s, strength, {0.7, -0.4});
  EXPECT_NEAR(std::hypot(f.x() / strength, f.y() / (0.6 * strength)), 1.0, 1e-9);
  // A small displacement mobilises each direction in proportion to its modulus:
  // along the lateral axis, the lateral modulus sets the force.
  const double small = 1e-4;
  EXPECT_NEAR(PadShearForce(s, strength, {0.0, small}).y(),
              -0.6 * strength * JanosiHanamotoFraction(small, s.lateral_shear_modulus_m), 1e-9);
}

// A station pushed sideways (or along) at constant speed with no track motion,
// integrated until steady: the force reaches that direction's strength, the
// lateral one with the bulldozing added; the damping vanishes once steady.
Eigen::Vector2d SteadyPush(const sim::SoilPoint& soil, const StationLoad& load,
                           const Eigen::Vector2d& v_pad) {
  StationKinematics kin;
  kin.v_pad_mps = v_pad;
  Eigen::Vector2d shear = Eigen::Vector2d::Zero(), f = Eigen::Vector2d::Zero();
  for (int step = 0; step < 2000; ++step) f = StepStationShear(soil, kin, load, 0.01, 1e-3, &shear);
  return f;
}

TEST(TerramechanicsTest, BulldozingAddsToTheLateralStrengthOnly) {
  sim::SoilPoint s = Soil("lete_sand");
  s.lateral_strength_ratio = 0.8;
  StationLoad load;
  load.normal_n = 30.0;
  load.area_m2 = 0.009;
  load.bulldozing_n = 12.0;
  const double strength = ShearStrength(s, load.normal_n, load.area_m2);
  // The shear memory is bounded at six moduli, so a sliding pad holds at least
  // 1 − e^(−6) of the strength, and the ellipse caps it at the strength.
  const double mobilised = 1.0 - std::exp(-6.0);
  const double lateral = -SteadyPush(s, load, {0.0, 0.1}).y();
  EXPECT_GE(lateral, (0.8 * strength + 12.0) * mobilised);
  EXPECT_LE(lateral, 0.8 * strength + 12.0 + 1e-9);
  const double along = -SteadyPush(s, load, {0.1, 0.0}).x();
  EXPECT_GE(along, strength * mobilised);
  EXPECT_LE(along, strength + 1e-9);
  // Unloaded and without cohesion: no force at all.
  sim::SoilPoint loose = Soil("dry_sand");
  load.normal_n = 0.0;
  EXPECT_EQ(SteadyPush(loose, load, {0.1, 0.1}), Eigen::Vector2d::Zero());
}

TEST(TerramechanicsTest, BekkerSinkageInvertsThePressureSinkageLaw) {
  const double b = 0.1;
  for (const sim::TerrainMaterial& m : sim::BuiltinMaterials()) {
    const sim::SoilPoint s = sim::SoilOf(m);
    if (s.IsRigid()) {
      EXPECT_EQ(BekkerSinkage(s, 1e4, b), 0.0) << m.name;
      continue;
    }
    for (double p : {1e3, 4e3, 2e4}) {
      const double z = BekkerSinkage(s, p, b);
      EXPECT_GT(z, 0.0) << m.name;
      EXPECT_NEAR((s.bekker_kc / b + s.bekker_kphi) * std::pow(z, s.bekker_n), p, 1e-9 * p)
          << m.name;
    }
  }
}

TEST(TerramechanicsTest, CompactionResistanceIsTheWorkOfMakingTheRut) {
  // R = ∫0^z b p(z') dz' = b k z^(n+1)/(n+1): check against a numeric integral.
  const sim::SoilPoint m = Soil("lete_sand");
  const double b = 0.1, z = 0.01, k = m.bekker_kc / b + m.bekker_kphi;
  double integral = 0.0;
  const int steps = 100000;
  for (int i = 0; i < steps; ++i) {
    const double zi = (i + 0.5) * z / steps;
    integral += b * k * std::pow(zi, m.bekker_n) * z / steps;
  }
  EXPECT_NEAR(CompactionResistance(m, z, b), integral, 1e-6 * integral);
  EXPECT_EQ(CompactionResistance(Soil("paving"), z, b), 0.0);
}

TEST(TerramechanicsTest, SlipSinkageFollowsLyasko) {
  EXPECT_DOUBLE_EQ(SlipSinkageFactor(0.0), 1.0);
  EXPECT_DOUBLE_EQ(SlipSinkageFactor(-0.3), 1.0);  // braking: static sinkage
  EXPECT_DOUBLE_EQ(SlipSinkageFactor(1.0), 4.0);   // (1 + 1) / (1 − 0.5)
  EXPECT_DOUBLE_EQ(SlipSinkageFactor(0.2), 1.2 / 0.9);
  double last = 1.0;
  for (double i = 0.05; i <= 1.0; i += 0.05) {
    EXPECT_GT(SlipSinkageFactor(i), last);
    last = SlipSinkageFactor(i);
  }
}

TEST(TerramechanicsTest, BearingCapacityFactorsMatchTheirTables) {
  // Vesić (1973) / Prandtl–Reissner tabulated values at φ = 30° and 20°, and the
  // cohesive limit N_c → π + 2 at φ = 0.
  const sim::BearingCapacityFactors f30 = sim::BearingCapacity(std::tan(30.0 * M_PI / 180.0));
  EXPECT_NEAR(f30.n_q, 18.40, 0.01);
  EXPECT_NEAR(f30.n_c, 30.14, 0.01);
  EXPECT_NEAR(f30.n_gamma, 22.40, 0.01);
  const sim::BearingCapacityFactors f20 = sim::BearingCapacity(std::tan(20.0 * M_PI / 180.0));
  EXPECT_NEAR(f20.n_q, 6.40, 0.01);
  EXPECT_NEAR(f20.n_c, 14.83, 0.01);
  EXPECT_NEAR(f20.n_gamma, 5.39, 0.01);
  EXPECT_NEAR(sim::BearingCapacity(0.0).n_c, M_PI + 2.0, 1e-12);
}

TEST(TerramechanicsTest, BulldozingResistanceIsBekkersPassivePressure) {
  sim::SoilPoint s = Soil("lete_sand");
  const double z = 0.02, width = 0.1, cos2 = 1.0 / (1.0 + s.tan_phi * s.tan_phi);
  const sim::BearingCapacityFactors f = sim::BearingCapacity(s.tan_phi);
  const double k_pc = (f.n_c - s.tan_phi) * cos2;
  const double k_pgamma = (2.0 * f.n_gamma / s.tan_phi + 1.0) * cos2;
  EXPECT_NEAR(
      BulldozingResistance(s, z, width),
      width * (0.67 * s.cohesion_pa * z * k_pc + 0.5 * z * z * s.unit_weight_npm3 * k_pgamma),
      1e-9);
  EXPECT_EQ(BulldozingResistance(s, 0.0, width), 0.0);
  EXPECT_EQ(BulldozingResistance(Soil("hard_floor"), z, width), 0.0);
  // Quadratic in depth without cohesion, linear with cohesion alone.
  s.cohesion_pa = 0.0;
  EXPECT_NEAR(BulldozingResistance(s, 2 * z, width), 4.0 * BulldozingResistance(s, z, width), 1e-9);
}

// Wong, Theory of Ground Vehicles, eq. (2.56) for a uniform pressure distribution:
// F = (cA + W tan φ)[1 − K/(iL)(1 − e^(−iL/K))].
double WongThrust(const sim::SoilPoint& s, double area, double weight, double i, double l) {
  return (s.cohesion_pa * area + weight * s.tan_phi) *
         (1.0 - s.shear_modulus_m / (i * l) * (1.0 - std::exp(-i * l / s.shear_modulus_m)));
}

// One track in steady slip i: stations at the midpoints of equal segments, each
// carrying W/n, integrated with StepStationShear until the shear is steady.
double SimulatedThrust(const sim::SoilPoint& s, int n, double length, double width, double weight,
                       double i) {
  const double u = 0.4, v = (1.0 - i) * u, dt = 1e-3;
  std::vector<Eigen::Vector2d> shear(static_cast<std::size_t>(n), Eigen::Vector2d::Zero());
  double thrust = 0.0;
  for (int step = 0; step < 20000; ++step) {  // 20 s: the rear pad renews in 1.4 s
    thrust = 0.0;
    for (int k = 0; k < n; ++k) {
      StationKinematics kin;
      kin.v_pad_mps = {v - u, 0.0};
      kin.track_speed_mps = u;
      kin.lead_m = (k + 0.5) * length / n;  // from the front
      StationLoad load;
      load.normal_n = weight / n;
      load.area_m2 = length * width / n;
      const Eigen::Vector2d f =
          StepStationShear(s, kin, load, 0.01, dt, &shear[static_cast<std::size_t>(k)]);
      thrust += f.x();
    }
  }
  return thrust;
}

TEST(TerramechanicsTest, SteadySlipThrustMatchesWongsClosedForm) {
  const sim::SoilPoint sand = Soil("lete_sand");
  const double length = 0.55, width = 0.1, weight = 196.2;  // one track of the 40 kg robot
  const int n = 32;
  for (double i : {0.02, 0.10, 0.40}) {
    const double closed = WongThrust(sand, length * width, weight, i, length);
    const double simulated = SimulatedThrust(sand, n, length, width, weight, i);
    EXPECT_NEAR(simulated / closed, 1.0, 0.02) << "slip " << i;
  }
}

TEST(TerramechanicsTest, BuiltinMaterialsAreValidAndNamed) {
  for (const sim::TerrainMaterial& m : sim::BuiltinMaterials()) {
    EXPECT_NO_THROW(m.Validate()) << m.name;
  }
  EXPECT_THROW(sim::BuiltinMaterial("marshmallow"), std::invalid_argument);
}

}  // namespace
}  // namespace trackbed::robot
