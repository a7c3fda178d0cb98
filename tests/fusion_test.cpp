// Wheel odometry with slip (Ham et al. eqs. 1–6) and the fuzzy fusion weight (Table 1).
#include <cmath>

#include <gtest/gtest.h>

#include "trackbed/estimation/fusion_weight_rise.h"
#include "trackbed/estimation/fuzzy_fusion.h"
#include "trackbed/estimation/wheel_odometry.h"

namespace trackbed::estimation {
namespace {

// Ticks of a sprocket turning at `omega` rad/s for `t` s (4096 per rev).
std::int64_t Ticks(double omega, double t) {
  return static_cast<std::int64_t>(std::floor(omega * t / (2 * M_PI) * 4096));
}

TEST(WheelOdometryTest, StraightLineWithoutSlipIsPlainOdometry) {
  WheelOdometry odo({}, {});
  for (int k = 0; k <= 1000; ++k)
    odo.AddEncoderSample(0.01 * k, Ticks(4.0, 0.01 * k), Ticks(4.0, 0.01 * k));
  EXPECT_NEAR(odo.pose().x, 4.0, 1e-3);  // 0.4 m/s for 10 s
  EXPECT_NEAR(odo.pose().y, 0.0, 1e-9);
  EXPECT_NEAR(odo.forward_mps(), 0.4, 1e-2);
}

TEST(WheelOdometryTest, TurnInPlaceUsesTheEffectiveGauge) {
  WheelOdometryOptions o;
  o.icr_expansion = 1.25;
  WheelOdometry odo(o, {});
  for (int k = 0; k <= 500; ++k)
    odo.AddEncoderSample(0.01 * k, Ticks(-2.0, 0.01 * k), Ticks(2.0, 0.01 * k));
  // Track speeds ±0.2 m/s, B_eff = 0.625 m: 0.64 rad/s for 5 s.
  EXPECT_NEAR(odo.pose().yaw, geometry::WrapAngle(3.2), 2e-3);
}

TEST(WheelOdometryTest, MeasuredVelocityRevealsSlipAndCorrectsTheOdometry) {
  // The tracks turn at 0.4 m/s but the robot makes 0.36 m/s: slip −0.04 m/s on both.
  WheelOdometry with_slip({}, {});
  WheelOdometryOptions plain_options;
  plain_options.estimate_slip = false;
  WheelOdometry plain(plain_options, {});
  for (int k = 0; k <= 1000; ++k) {
    const double t = 0.01 * k;
    for (WheelOdometry* o : {&with_slip, &plain})
      o->AddEncoderSample(t, Ticks(4.0, t), Ticks(4.0, t));
    if (k > 0 && k % 10 == 0) {
      with_slip.AddMeasuredVelocity(t - 0.1, t, 0.36, 0.0);
      plain.AddMeasuredVelocity(t - 0.1, t, 0.36, 0.0);
    }
  }
  EXPECT_NEAR(with_slip.slip().left_mps, -0.04, 2e-3);
  EXPECT_NEAR(with_slip.slip().right_mps, -0.04, 2e-3);
  // Corrected, once the filter (τ = 0.2 s) has settled: 0.04 m/s of slip unseen over
  // the first interval (0.1 s) and the filter's lag (0.2 s), 0.012 m.
  EXPECT_NEAR(with_slip.pose().x, 3.6 + 0.012, 0.004);
  EXPECT_NEAR(plain.pose().x, 4.0, 1e-3);  // the baseline cannot see slip
  EXPECT_EQ(plain.slip().max_abs_mps(), 0.0);
}

TEST(WheelOdometryTest, SlipFilterTakesEachMeasurementWithItsTimeConstant) {
  // A slip of −0.10 m/s appears at once; one 0.1 s measurement moves the estimate by
  // 1 − exp(−0.1 / τ) of it.
  for (double tau : {0.0, 0.2, 0.5}) {
    WheelOdometryOptions o;
    o.slip_filter_time_s = tau;
    WheelOdometry odo(o, {});
    for (int k = 0; k <= 100; ++k)
      odo.AddEncoderSample(0.01 * k, Ticks(4.0, 0.01 * k), Ticks(4.0, 0.01 * k));
    odo.AddMeasuredVelocity(0.9, 1.0, 0.30, 0.0);
    const double gain = tau > 0.0 ? 1.0 - std::exp(-0.1 / tau) : 1.0;
    EXPECT_NEAR(odo.slip().left_mps, -0.10 * gain, 2e-3) << "tau " << tau;
    EXPECT_NEAR(odo.slip().right_mps, -0.10 * gain, 2e-3) << "tau " << tau;
  }
}

TEST(WheelOdometryTest, HeldSlipDecaysWithoutMeasurements) {
  WheelOdometryOptions o;
  o.slip_filter_time_s = 0.0;  // take the one measurement whole
  WheelOdometry odo(o, {});
  for (int k = 0; k <= 100; ++k)
    odo.AddEncoderSample(0.01 * k, Ticks(4.0, 0.01 * k), Ticks(4.0, 0.01 * k));
  odo.AddMeasuredVelocity(0.9, 1.0, 0.30, 0.0);
  const double held = odo.slip().left_mps;
  EXPECT_NEAR(held, -0.10, 2e-3);
  for (int k = 101; k <= 400; ++k)
    odo.AddEncoderSample(0.01 * k, Ticks(4.0, 0.01 * k), Ticks(4.0, 0.01 * k));
  // Fresh for 0.3 s, then decaying: 2.7 s at τ = 3 s.
  EXPECT_NEAR(odo.slip().left_mps, held * std::exp(-2.7 / 3.0), 2e-3);
}

TEST(FuzzyFusionTest, TableOneCornersAndMonotonicity) {
  FuzzyFusionWeight fuzzy;
  // Few features and little slip: trust the wheels (excellent); many features and
  // much slip: trust vision (poor).
  const double few_small = fuzzy.Weight(0.0, 0.0);
  const double many_large = fuzzy.Weight(0.3, 1000.0);
  EXPECT_GT(few_small, 0.8);
  EXPECT_LT(many_large, 0.2);
  // Table 1's other corners: very less features + very large slip = fair;
  // very plenty + very small = fair.
  EXPECT_NEAR(fuzzy.Weight(0.3, 0.0), fuzzy.Weight(0.0, 1000.0), 1e-6);
  EXPECT_GT(fuzzy.Weight(0.3, 0.0), many_large);
  EXPECT_LT(fuzzy.Weight(0.3, 0.0), few_small);
  // More slip → lower w; more features → lower w. A Mamdani centroid is not
  // strictly monotone where one clipped set moves its own centroid (by < 0.01
  // here), so each sweep may rise by that much but must fall overall.
  for (double features : {0.0, 30.0, 100.0, 500.0}) {
    double last = 2.0;
    for (double slip = 0.0; slip <= 0.3; slip += 0.01) {
      const double w = fuzzy.Weight(slip, features);
      EXPECT_LE(w, last + 0.01) << "slip " << slip << " features " << features;
      last = w;
    }
    EXPECT_GT(fuzzy.Weight(0.0, features) - fuzzy.Weight(0.3, features), 0.1) << features;
  }
  for (double slip : {0.0, 0.03, 0.08, 0.2}) {
    double last = 2.0;
    for (double features = 0.0; features <= 400.0; features += 5.0) {
      const double w = fuzzy.Weight(slip, features);
      EXPECT_LE(w, last + 0.01) << "slip " << slip << " features " << features;
      last = w;
    }
    EXPECT_GT(fuzzy.Weight(slip, 0.0) - fuzzy.Weight(slip, 400.0), 0.1) << slip;
  }
}

// Every rule of Table 1 (Ham et al. 2012), one at a time: at the peaks of one slip
// term and one feature term no other set of either input is active, so exactly one
// rule fires with strength 1 and w is the centroid of its output term, (a + b + c)/3
// of the triangle. The table below is the paper's, restated here independently of
// the rule file: rows are the features terms, columns the slip terms.
TEST(FuzzyFusionTest, EachOfTheTwentyFiveRulesGivesItsOutputTermAtThePeaks) {
  enum Term { kPoor, kFair, kGood, kVeryGood, kExcellent };
  const double centroid[] = {(0.0 + 0.1 + 0.3) / 3.0, (0.1 + 0.3 + 0.5) / 3.0,
                             (0.3 + 0.5 + 0.7) / 3.0, (0.5 + 0.7 + 0.9) / 3.0,
                             (0.7 + 0.9 + 1.0) / 3.0};
  // Peaks (plateau centres for the trapezoids) of the rule file's sets.
  const double slip_peak[] = {0.005, 0.025, 0.045, 0.070, 0.200};  // very_small … very_large
  const double feature_peak[] = {4.0, 20.0, 40.0, 80.0, 500.0};    // very_less … very_plenty
  // Table 1: w for [features][slip], slip from very_small to very_large.
  const Term table[5][5] = {
      {kExcellent, kVeryGood, kGood, kGood, kFair},  // very less features
      {kVeryGood, kGood, kGood, kFair, kPoor},       // less
      {kGood, kGood, kFair, kPoor, kPoor},           // medium
      {kGood, kFair, kPoor, kPoor, kPoor},           // plenty
      {kFair, kPoor, kPoor, kPoor, kPoor},           // very plenty
  };
  FuzzyFusionWeight fuzzy;
  for (int f = 0; f < 5; ++f) {
    for (int v = 0; v < 5; ++v) {
      EXPECT_NEAR(fuzzy.Weight(slip_peak[v], feature_peak[f]), centroid[table[f][v]], 5e-3)
          << "features term " << f << ", slip term " << v;
    }
  }
}

TEST(FuzzyFusionTest, BadRuleFilesAreRejectedWithTheirName) {
  EXPECT_THROW(FuzzyFusionWeight("Engine: x\nInputVariable: a\n  range: 0 1\n", "mine.fll"),
               std::invalid_argument);
  try {
    FuzzyFusionWeight::FromFile("/nonexistent/rules.fll");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/rules.fll"), std::string::npos);
  }
}

TEST(FusedOdometryTest, BlendsIncrementsAndFallsBackToWheelsWithoutVision) {
  FusedOdometry fused({});
  fused.Add({0.10, 0.0, 0.0}, geometry::Pose2{0.06, 0.0, 0.0}, 0.25);  // 0.25·0.10 + 0.75·0.06
  EXPECT_NEAR(fused.pose().x, 0.07, 1e-12);
  fused.Add({0.10, 0.0, 0.0}, std::nullopt, 0.25);
  EXPECT_NEAR(fused.pose().x, 0.17, 1e-12);
}

// The applied weight falls to the rule's at once and rises toward it with τ: 3 s after
// the slip ends it has climbed 1 − 1/e of the way back to the wheels.
TEST(FusionWeightRiseTest, FallsAtOnceAndRisesWithItsTimeConstant) {
  FusionWeightRise w(3.0);
  EXPECT_EQ(w.weight(), 1.0);
  EXPECT_EQ(w.Update(0.2, 0.1), 0.2);  // slip: down in one frame
  double expected = 0.2;
  for (int k = 1; k <= 30; ++k) {  // 3 s of frames at 10 Hz with the rule back at 1
    expected += (1.0 - std::exp(-0.1 / 3.0)) * (1.0 - expected);
    EXPECT_NEAR(w.Update(1.0, 0.1), expected, 1e-15) << k;
  }
  EXPECT_NEAR(w.weight(), 1.0 - 0.8 * std::exp(-1.0), 1e-12);
  // A lower rule weight in the middle of the rise takes effect at once …
  EXPECT_EQ(w.Update(0.5, 0.1), 0.5);
  // … and a higher one only partly: after one frame 3.3 % of the way.
  EXPECT_NEAR(w.Update(0.9, 0.1), 0.5 + (1.0 - std::exp(-0.1 / 3.0)) * 0.4, 1e-15);
}

TEST(FusionWeightRiseTest, WithoutARiseTimeOrTimeItFollowsTheRule) {
  FusionWeightRise none(0.0);
  EXPECT_EQ(none.Update(0.1, 0.1), 0.1);
  EXPECT_EQ(none.Update(0.9, 0.1), 0.9);
  FusionWeightRise w(3.0);
  EXPECT_EQ(w.Update(0.3, 0.1), 0.3);
  EXPECT_EQ(w.Update(0.8, 0.0), 0.8);  // no time between frames: nothing to smooth over
}

}  // namespace
}  // namespace trackbed::estimation
