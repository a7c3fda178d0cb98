// A long run holds what a short one holds: the park without the camera for 40 minutes
// (16 laps, 960 m), the sizes of everything that could grow with the run's length read
// every 4 minutes (ClosedLoop::held_sizes). Longer soaks, with memory and CPU time, are in
// bench/ (bench/long_run_cost.cpp).
#include <algorithm>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/runner/closed_loop.h"
#include "trackbed/runner/plot_decimation.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::runner {
namespace {

namespace fs = std::filesystem;

TEST(SoakTest, FortyMinutesOfTheParkHoldBoundedScoresAndPlots) {
  const scenario::Scenario s = scenario::LoadScenario(TRACKBED_SOURCE_DIR "/scenes/outdoor.yaml",
                                                      {{"duration_s", "2400"},
                                                       {"drive.laps", "100"},
                                                       {"robot.stereo.enabled", "false"},
                                                       {"outputs.mcap", "false"}});
  const fs::path dir = fs::temp_directory_path() / "trackbed_soak_test";
  fs::remove_all(dir);
  ClosedLoopOptions options;
  options.dir = dir;
  ClosedLoop loop(s, std::move(options));
  loop.Start();
  std::vector<HeldSizes> sizes;
  double next_s = 240.0;
  while (!loop.done()) {
    if (loop.Step().t_s >= next_s) {
      sizes.push_back(loop.held_sizes());
      next_s += 240.0;
    }
  }
  const RunMetrics m = loop.Finish();
  ASSERT_TRUE(m.completed) << m.stop_reason;
  EXPECT_EQ(m.stop_reason, "duration reached");
  EXPECT_GT(m.distance_m, 900.0);
  ASSERT_EQ(sizes.size(), 10u);
  for (const HeldSizes& h : sizes) {
    // Three estimators' windows of 10 m of path at 100 Hz and 0.4 m/s: 2500 poses each
    // (more where the robot slows in the turns).
    EXPECT_GT(h.scoring_window_poses, 3u * 2000u);
    EXPECT_LT(h.scoring_window_poses, 3u * 4000u);
    EXPECT_LT(h.largest_plot_series, kPlotCapacity);
    EXPECT_LE(h.icr_fit_groups, 40u);
  }
  // The plots filled up (20000 points of 10 Hz at 2000 s) and were thinned: 40 minutes
  // hold fewer points than 20.
  EXPECT_EQ(sizes[4].largest_plot_series, 12001u);  // 1200 s at 10 Hz, t = 0 included
  EXPECT_LT(sizes.back().largest_plot_series, sizes[7].largest_plot_series);
  // The park's loop turns at every corner: the ICR fit's groups filled and merged.
  EXPECT_GE(sizes.back().icr_fit_groups, 20u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace trackbed::runner
