// Rank correlation, rank violation and the transfer study's figures on constructed
// outcomes whose values are known by hand (experiments/rank_correlation.h,
// experiments/transfer_study.h; docs/transfer.md).
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/common/option_error.h"
#include "trackbed/experiments/rank_correlation.h"
#include "trackbed/experiments/transfer_study.h"

namespace {

using namespace trackbed::experiments;

TEST(RankCorrelationTest, AverageRanksGiveTiesTheMeanOfTheirRanks) {
  EXPECT_EQ(AverageRanks({10, 20, 20, 30}), (std::vector<double>{1, 2.5, 2.5, 4}));
  EXPECT_EQ(AverageRanks({3, 1, 2}), (std::vector<double>{3, 1, 2}));
  EXPECT_EQ(AverageRanks({5, 5, 5}), (std::vector<double>{2, 2, 2}));
}

TEST(RankCorrelationTest, IdenticalOutcomesAgreeFully) {
  const std::vector<double> real = {0.9, 1.4, 2.0, 3.7, 8.1};
  EXPECT_DOUBLE_EQ(SpearmanRho(real, real), 1.0);
  EXPECT_DOUBLE_EQ(PearsonR(real, real), 1.0);
  EXPECT_DOUBLE_EQ(MeanMaximumRankViolation(real, real), 0.0);
  // Any increasing map of the outcomes ranks them alike: rho 1, MMRV 0, r below 1.
  std::vector<double> squared;
  for (double x : real) squared.push_back(x * x);
  EXPECT_DOUBLE_EQ(SpearmanRho(real, squared), 1.0);
  EXPECT_DOUBLE_EQ(MeanMaximumRankViolation(real, squared), 0.0);
  EXPECT_LT(PearsonR(real, squared), 0.999);
}

TEST(RankCorrelationTest, ReversedOutcomesGiveMinusOneAndTheWorstViolations) {
  // Real 1..4, simulated 4..1: each item's worst violation is its farthest item,
  // max(i - 1, 4 - i) / 3: 1, 2/3, 2/3, 1 → MMRV 5/6.
  const std::vector<double> real = {1, 2, 3, 4}, sim = {4, 3, 2, 1};
  EXPECT_DOUBLE_EQ(SpearmanRho(real, sim), -1.0);
  EXPECT_DOUBLE_EQ(PearsonR(real, sim), -1.0);
  EXPECT_DOUBLE_EQ(MeanMaximumRankViolation(real, sim), 5.0 / 6.0);
  // Five items: 1, 3/4, 1/2, 3/4, 1 → 0.8.
  EXPECT_DOUBLE_EQ(MeanMaximumRankViolation({1, 2, 3, 4, 5}, {5, 4, 3, 2, 1}), 0.8);
}

TEST(RankCorrelationTest, OneSwapGivesTheValuesComputedByHand) {
  // Items 2 and 3 swapped: rank differences 0, 1, -1, 0, Σd² = 2,
  // rho = 1 - 6·2 / (4·(16 - 1)) = 0.8; evenly spaced values give r = 0.8 too. Items 2
  // and 3 each have one violation of real difference 1 over the range 3: MMRV =
  // (1/3 + 1/3) / 4 = 1/6.
  const std::vector<double> real = {1, 2, 3, 4}, sim = {1, 3, 2, 4};
  EXPECT_NEAR(SpearmanRho(real, sim), 0.8, 1e-15);
  EXPECT_NEAR(PearsonR(real, sim), 0.8, 1e-15);
  EXPECT_DOUBLE_EQ(MeanMaximumRankViolation(real, sim), 1.0 / 6.0);
}

TEST(RankCorrelationTest, ViolationsAreWeightedByTheRealDifferenceOverTheRange) {
  // The same swap where the swapped items are 2 apart in a range of 7: MMRV =
  // (2/7 + 2/7) / 4 = 1/7. Pearson by hand: deviations from 3.75 (-2.75, -1.75, 0.25,
  // 4.25) and (-2.75, 0.25, -1.75, 4.25): Σxy = 24.75, Σx² = Σy² = 28.75, r = 99/115.
  const std::vector<double> real = {1, 2, 4, 8}, sim = {1, 4, 2, 8};
  EXPECT_DOUBLE_EQ(MeanMaximumRankViolation(real, sim), 1.0 / 7.0);
  EXPECT_NEAR(PearsonR(real, sim), 99.0 / 115.0, 1e-15);
  EXPECT_NEAR(SpearmanRho(real, sim), 0.8, 1e-15);
}

TEST(RankCorrelationTest, TiesAndDegenerateInputs) {
  // Ties in the simulated outcomes: ranks (1, 2, 3, 4) against (1.5, 1.5, 3, 4).
  // Pearson of those: deviations (-1.5, -0.5, 0.5, 1.5) and (-1, -1, 0.5, 1.5):
  // Σxy = 1.5 + 0.5 + 0.25 + 2.25 = 4.5, Σx² = 5, Σy² = 4.5 → rho = 4.5 / sqrt(22.5).
  EXPECT_NEAR(SpearmanRho({1, 2, 3, 4}, {7, 7, 8, 9}), 4.5 / std::sqrt(22.5), 1e-15);
  // A tie in the simulation counts against the pair it leaves unordered (SIMPLER's
  // test: (sim_i < sim_j) != (real_i < real_j)): item 1 (real 1, sim 7) against item 2
  // (real 2, sim 7): 1/3; nothing else.
  EXPECT_DOUBLE_EQ(MeanMaximumRankViolation({1, 2, 3, 4}, {7, 7, 8, 9}), 1.0 / 12.0);
  EXPECT_TRUE(std::isnan(PearsonR({1, 2, 3}, {5, 5, 5})));
  EXPECT_TRUE(std::isnan(SpearmanRho({1}, {1})));
  EXPECT_DOUBLE_EQ(MeanMaximumRankViolation({2, 2, 2}, {1, 2, 3}), 0.0);
  EXPECT_THROW(PearsonR({1, 2}, {1, 2, 3}), std::invalid_argument);
  EXPECT_THROW(SpearmanRho({1, NAN, 3}, {1, 2, 3}), std::invalid_argument);
}

// A table whose configuration k has, on each of `sequences` sequences, `frames` frames of
// value outcome[k] + a small frame-dependent ripple that never changes the order.
OutcomeTable Table(const std::vector<std::string>& names, const std::vector<double>& outcome,
                   int sequences, int frames) {
  OutcomeTable t;
  for (std::size_t k = 0; k < names.size(); ++k) {
    for (int s = 0; s < sequences; ++s) {
      SequenceOutcome seq{"seq" + std::to_string(s), {}, {}};
      for (int f = 0; f < frames; ++f) {
        seq.frames.push_back(f);
        seq.values.push_back(outcome[k] + 0.01 * ((f * 7 + s * 3) % 5));
      }
      t[names[k]].push_back(seq);
    }
  }
  return t;
}

const std::vector<std::string> kNames = {"a", "b", "c", "d", "e"};

TEST(TransferStudyTest, IdenticalTablesAgreeFullyWithinTheirIntervals) {
  const OutcomeTable t = Table(kNames, {1.0, 1.2, 1.4, 2.0, 3.0}, 2, 20);
  TransferOptions o;
  o.resamples = 200;
  const TransferFigures f = TransferStudy(t, t, o);
  EXPECT_EQ(f.configurations, kNames);
  EXPECT_DOUBLE_EQ(f.all.spearman.value, 1.0);
  EXPECT_DOUBLE_EQ(f.all.pearson.value, 1.0);
  EXPECT_DOUBLE_EQ(f.all.mmrv.value, 0.0);
  // The ripple (under 0.05) never reorders configurations 0.2 apart: every frame
  // resample agrees fully; resampled configurations repeat some, and still agree.
  EXPECT_DOUBLE_EQ(f.all.spearman.frames.low, 1.0);
  EXPECT_DOUBLE_EQ(f.all.mmrv.both.high, 0.0);
  EXPECT_GT(f.all.spearman.both.resamples, 150);
  // Near the best: within 1.5 × 1.0 → a, b, c.
  EXPECT_EQ(f.near_best.configurations, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_DOUBLE_EQ(f.near_best.spearman.value, 1.0);
  // The ceiling: the halves (even and odd 5-frame blocks) order the configurations alike.
  ASSERT_TRUE(f.real_ceiling.available);
  EXPECT_DOUBLE_EQ(f.real_ceiling.spearman, 1.0);
  EXPECT_DOUBLE_EQ(f.real_ceiling.spearman_full, 1.0);
}

TEST(TransferStudyTest, ReversedAndSwappedTablesGiveTheirKnownPointValues) {
  const std::vector<double> real = {1, 2, 3, 4, 5};
  const OutcomeTable r = Table(kNames, real, 1, 10);
  TransferOptions o;
  o.resamples = 100;
  const TransferFigures reversed = TransferStudy(r, Table(kNames, {5, 4, 3, 2, 1}, 1, 10), o);
  EXPECT_DOUBLE_EQ(reversed.all.spearman.value, -1.0);
  EXPECT_NEAR(reversed.all.mmrv.value, 0.8, 1e-12);
  const TransferFigures swapped = TransferStudy(r, Table(kNames, {1, 3, 2, 4, 5}, 1, 10), o);
  // n = 5, Σd² = 2: rho = 1 - 12/120 = 0.9; MMRV = (1/4 + 1/4) / 5 = 0.1.
  EXPECT_NEAR(swapped.all.spearman.value, 0.9, 1e-12);
  EXPECT_NEAR(swapped.all.pearson.value, 0.9, 1e-12);
  EXPECT_NEAR(swapped.all.mmrv.value, 0.1, 1e-12);
}

TEST(TransferStudyTest, TheSameSeedGivesTheSameIntervals) {
  const OutcomeTable real = Table(kNames, {1, 2, 3, 4, 5}, 1, 30);
  OutcomeTable sim = Table(kNames, {1, 3, 2, 5, 4}, 3, 30);
  sim["c"][1].values[4] = 9.0;  // one outlying frame
  TransferOptions o;
  o.resamples = 300;
  const TransferFigures a = TransferStudy(real, sim, o), b = TransferStudy(real, sim, o);
  EXPECT_EQ(a.all.spearman.both.low, b.all.spearman.both.low);
  EXPECT_EQ(a.all.mmrv.both.high, b.all.mmrv.both.high);
  EXPECT_LE(a.all.spearman.both.low, a.all.spearman.value);
  EXPECT_GE(a.all.spearman.both.high, a.all.spearman.value);
  o.seed = 2;
  const TransferFigures c = TransferStudy(real, sim, o);
  EXPECT_DOUBLE_EQ(c.all.spearman.value, a.all.spearman.value);
}

TEST(TransferStudyTest, AConfigurationOnOneSideOnlyIsNamed) {
  const OutcomeTable real = Table(kNames, {1, 2, 3, 4, 5}, 1, 10);
  OutcomeTable sim = real;
  sim.erase("d");
  try {
    TransferStudy(real, sim);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "configuration 'd' has real outcomes but no simulated ones");
  }
  sim = real;
  sim["extra"] = sim["a"];
  EXPECT_THROW(TransferStudy(real, sim), std::invalid_argument);
  TransferOptions o;
  o.resamples = 10;
  EXPECT_THROW(TransferStudy(real, real, o), trackbed::OptionError);
}

TEST(TransferStudyTest, WithoutFrameIndicesThereIsNoCeilingAndNoFrameResampling) {
  OutcomeTable t;
  const std::vector<double> v = {3, 1, 2, 5};
  for (std::size_t k = 0; k < v.size(); ++k) t[kNames[k]].push_back({"log", {}, {v[k]}});
  TransferOptions o;
  o.resamples = 100;
  const TransferFigures f = TransferStudy(t, t, o);
  EXPECT_FALSE(f.real_ceiling.available);
  EXPECT_DOUBLE_EQ(f.all.spearman.frames.low, 1.0);  // nothing to resample: the point value
  EXPECT_DOUBLE_EQ(f.all.spearman.frames.high, 1.0);
}

}  // namespace
