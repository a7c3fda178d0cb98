// Plots of data that barely move: a robot turning in place draws a map within a
// millimetre, a constant series a panel of no height. Both once drew ticks until the
// step no longer changed the tick; now they finish, with a readable axis.
#include "trackbed/plot/plots.h"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

namespace trackbed::plot {
namespace {

namespace fs = std::filesystem;

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "trackbed_plot_degenerate_span_test";
  fs::create_directories(dir);
  return dir / name;
}

TEST(PlotDegenerateSpanTest, APathTurningInPlaceIsDrawnOnAMetre) {
  // Near the start at the origin, a few units of the last place apart.
  PlotSeries turning{"fused", {}};
  double x = 1e-5, y = -2e-5;
  for (int k = 0; k < 50; ++k) {
    turning.points.emplace_back(x, y);
    x = std::nextafter(x, 1.0);
    y = std::nextafter(y, -1.0);
  }
  const fs::path png = Scratch("map.png");
  WriteMapPlot(png, "turning in place", {turning}, {}, {{{1e-5, -2e-5}, "goal"}});
  const cv::Mat img = cv::imread(png.string());
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 1040);
  EXPECT_EQ(img.rows, 720);
}

TEST(PlotDegenerateSpanTest, ANearlyConstantSeriesGetsAPanel) {
  PlotSeries slip{"slip", {}};
  const double level = 1e-4;
  for (int k = 0; k < 50; ++k) {
    slip.points.emplace_back(0.1 * k, k % 2 == 0 ? level : std::nextafter(level, 1.0));
  }
  const fs::path png = Scratch("time.png");
  WriteTimePlot(png, "constant", {TimePanel{"slip [-]", {slip}}});
  EXPECT_FALSE(cv::imread(png.string()).empty());
}

}  // namespace
}  // namespace trackbed::plot
