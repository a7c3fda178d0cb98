// The progress checker every navigator gives up with (progress_checker.h): the stall
// clock, what counts as progress, the goal tolerance, stickiness, its options. Periods
// of 0.25 s add up exactly, so the stall falls on a known update.
#include <gtest/gtest.h>

#include "trackbed/common/option_error.h"
#include "trackbed/navigation/progress_checker.h"

namespace trackbed::navigation {
namespace {

constexpr double kDt = 0.25;
constexpr double kTolerance = 0.1;

ProgressCheckerOptions OneSecond() {
  ProgressCheckerOptions options;
  options.stall_time_s = 1.0;
  options.min_progress_m = 0.1;
  return options;
}

TEST(ProgressCheckerTest, StallsAfterTheStallTimeWithoutProgress) {
  ProgressChecker checker(OneSecond());
  EXPECT_FALSE(checker.Update(5.0, kTolerance, kDt));  // the first distance is the best
  for (int k = 1; k < 4; ++k) {
    EXPECT_FALSE(checker.Update(5.0, kTolerance, kDt)) << k * kDt << " s";
  }
  EXPECT_FALSE(checker.stalled());
  EXPECT_TRUE(checker.Update(5.0, kTolerance, kDt));  // 1 s without progress
  EXPECT_TRUE(checker.stalled());
}

TEST(ProgressCheckerTest, ProgressRestartsTheClock) {
  ProgressChecker checker(OneSecond());
  checker.Update(5.0, kTolerance, kDt);
  for (int k = 0; k < 3; ++k) checker.Update(5.0, kTolerance, kDt);  // 0.75 s
  EXPECT_FALSE(checker.Update(4.85, kTolerance, kDt));               // 0.15 m closer
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(checker.Update(4.85, kTolerance, kDt));
  EXPECT_TRUE(checker.Update(4.85, kTolerance, kDt));
}

TEST(ProgressCheckerTest, CreepingCloserByLessThanTheMinimumIsNoProgress) {
  // Every step is closer than the last, but together less than 0.1 m below the best
  // distance: a robot trembling in a trap does not keep its run alive.
  ProgressChecker checker(OneSecond());
  checker.Update(5.0, kTolerance, kDt);
  EXPECT_FALSE(checker.Update(4.95, kTolerance, kDt));
  EXPECT_FALSE(checker.Update(4.92, kTolerance, kDt));
  EXPECT_FALSE(checker.Update(4.91, kTolerance, kDt));
  EXPECT_TRUE(checker.Update(4.905, kTolerance, kDt));
}

TEST(ProgressCheckerTest, WithinTheGoalToleranceTheClockDoesNotRun) {
  // The final turn in place to the goal heading makes no progress in distance.
  ProgressChecker checker(OneSecond());
  for (int k = 0; k < 100; ++k) EXPECT_FALSE(checker.Update(0.05, kTolerance, kDt));
  EXPECT_FALSE(checker.stalled());
}

TEST(ProgressCheckerTest, OnceStalledStaysStalled) {
  ProgressChecker checker(OneSecond());
  for (int k = 0; k < 5; ++k) checker.Update(5.0, kTolerance, kDt);
  ASSERT_TRUE(checker.stalled());
  EXPECT_TRUE(checker.Update(1.0, kTolerance, kDt));
  EXPECT_TRUE(checker.Update(0.0, kTolerance, kDt));
}

TEST(ProgressCheckerTest, InvalidOptionsNameTheField) {
  ProgressCheckerOptions options;
  options.stall_time_s = 0.0;
  try {
    ProgressChecker checker(options);
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "stall_time_s");
  }
  options = {};
  options.min_progress_m = -0.1;
  try {
    options.Validate();
    FAIL() << "expected OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "min_progress_m");
  }
}

}  // namespace
}  // namespace trackbed::navigation
