// Height statistics of a scenario's terrain, and a shaded relief of it: what
// the ground of a scene is, without running it.
//
//   terrain_report SCENARIO.yaml [--set KEY=VALUE ...] [--png OUT.png]
//
// Prints the extent, the grid, the heights' range, mean and standard deviation,
// the slope's RMS and 95th percentile (per cell, from the triangulated
// surface's normals), and each material's share of the cells. The PNG is a
// top-down relief (one pixel per grid vertex, x to the right, y up), lit from
// the north-west and tinted by material.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bench_args.h"
#include "trackbed/common/split_mix.h"
#include "trackbed/scenario/scenario_yaml.h"
#include "trackbed/sim/terrain.h"

namespace {

using trackbed::sim::Terrain;

// One tint per material index (BGR): greys, greens, sands, browns.
const std::array<cv::Vec3d, 8> kPalette = {{{0.8, 0.8, 0.8},
                                            {0.6, 0.6, 0.65},
                                            {0.55, 0.8, 0.9},
                                            {0.45, 0.7, 0.85},
                                            {0.4, 0.55, 0.7},
                                            {0.35, 0.45, 0.6},
                                            {0.3, 0.7, 0.35},
                                            {0.45, 0.85, 0.5}}};

// Every grid vertex's height, row-major, computed once from the seed.
std::vector<double> GridHeights(const Terrain& t) {
  std::vector<double> h;
  h.reserve(static_cast<std::size_t>(t.cols()) * t.rows());
  for (int j = 0; j < t.rows(); ++j) {
    for (int i = 0; i < t.cols(); ++i) h.push_back(t.VertexHeight(i, j));
  }
  return h;
}

void PrintStatistics(const Terrain& t, const std::vector<double>& h) {
  double sum = 0.0, sum_sq = 0.0;
  const double n = static_cast<double>(h.size());
  for (const double z : h) sum += z;
  const double mean = sum / n;
  for (const double z : h) sum_sq += (z - mean) * (z - mean);
  std::vector<double> slopes;
  std::map<int, long> cells_per_material;
  const double c = t.cell_size_m();
  for (int j = 0; j + 1 < t.rows(); ++j) {
    for (int i = 0; i + 1 < t.cols(); ++i) {
      const double x = t.x_min() + (i + 0.5) * c, y = t.y_min() + (j + 0.5) * c;
      const double nz = t.Sample(x, y).normal.z();
      slopes.push_back(std::sqrt(std::max(1.0 - nz * nz, 0.0)) / nz);  // tan of the tilt
      ++cells_per_material[t.CellMaterial(i, j)];
    }
  }
  double slope_sq = 0.0;
  for (const double s : slopes) slope_sq += s * s;
  std::sort(slopes.begin(), slopes.end());
  std::printf("extent      [%.2f, %.2f] x [%.2f, %.2f] m, %d x %d grid points of %.3f m\n",
              t.x_min(), t.x_max(), t.y_min(), t.y_max(), t.cols(), t.rows(), c);
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  std::printf("height      min %.4f  max %.4f  mean %.4f  std %.4f m\n", *lo, *hi, mean,
              std::sqrt(sum_sq / n));
  std::printf("slope       rms %.4f  p95 %.4f  max %.4f (tan of the tilt)\n",
              std::sqrt(slope_sq / static_cast<double>(slopes.size())),
              slopes[slopes.size() * 95 / 100], slopes.back());
  for (const auto& [material, cells] : cells_per_material) {
    std::printf("material    %-28s %6.2f %% of the cells\n",
                t.materials()[static_cast<std::size_t>(material)].name.c_str(),
                100.0 * static_cast<double>(cells) / static_cast<double>(slopes.size()));
  }
}

cv::Mat Relief(const Terrain& t, double lo, double hi) {
  cv::Mat image(t.rows(), t.cols(), CV_8UC3);
  const double c = t.cell_size_m();
  const double span = std::max(hi - lo, 1e-9);
  for (int j = 0; j < t.rows(); ++j) {
    for (int i = 0; i < t.cols(); ++i) {
      const double x = t.x_min() + std::min(i + 0.5, t.cols() - 1.0) * c;
      const double y = t.y_min() + std::min(j + 0.5, t.rows() - 1.0) * c;
      const trackbed::sim::GroundSample g = t.Sample(x, y);
      // Lambert from the north-west, 45° up, with half the light ambient.
      const double light =
          0.5 + 0.5 * std::max(0.0, g.normal.dot(Eigen::Vector3d(-0.5, 0.5, 0.7071)));
      const double height = (g.height_m - lo) / span;
      const auto material = static_cast<std::size_t>(g.material - t.materials().data());
      const cv::Vec3d& colour = kPalette[material % kPalette.size()];
      cv::Vec3b& px = image.at<cv::Vec3b>(t.rows() - 1 - j, i);
      for (int k = 0; k < 3; ++k) {
        const double v = 255.0 * light * (0.6 + 0.4 * height) * colour[k];
        px[k] = static_cast<unsigned char>(std::clamp(v, 0.0, 255.0));
      }
    }
  }
  return image;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Height statistics and a shaded relief of a scenario's terrain"};
  std::string file, png;
  std::vector<std::string> sets;
  app.add_option("scenario", file, "Scenario file")->required();
  trackbed::bench::AddSetOption(app, &sets);
  app.add_option("--png", png, "Write the relief here");
  if (const std::optional<int> status = trackbed::bench::Parse(app, argc, argv)) return *status;
  try {
    std::vector<trackbed::scenario::Override> overrides;
    for (const std::string& s : sets) overrides.push_back(trackbed::scenario::ParseOverride(s));
    const trackbed::scenario::Scenario s = trackbed::scenario::LoadScenario(file, overrides);
    // The closed loop's terrain seed (runner/plant.cpp).
    const Terrain t(s.scene.terrain, trackbed::split_mix::Stream(s.seed, 0));
    const std::vector<double> heights = GridHeights(t);
    PrintStatistics(t, heights);
    const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
    if (!png.empty() && !cv::imwrite(png, Relief(t, *lo, *hi))) {
      std::fprintf(stderr, "terrain_report: could not write %s\n", png.c_str());
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "terrain_report: %s\n", e.what());
    return 1;
  }
  return 0;
}
