// Heights on a regular grid of sample points, bilinear between them (see elevation_grid.h).
#include "trackbed/sim/elevation_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace trackbed::sim {

ElevationGrid::ElevationGrid(int cols, int rows, const Eigen::Vector2d& first_m,
                             const Eigen::Vector2d& spacing_m, std::vector<double> heights_m)
    : cols_(cols),
      rows_(rows),
      first_(first_m),
      spacing_(spacing_m),
      heights_(std::move(heights_m)) {
  if (cols < 2 || rows < 2) {
    throw std::invalid_argument("ElevationGrid: needs at least 2 × 2 samples (got " +
                                std::to_string(cols) + " × " + std::to_string(rows) + ")");
  }
  if (!(spacing_.x() > 0.0 && spacing_.y() > 0.0) || !first_.allFinite()) {
    throw std::invalid_argument("ElevationGrid: the spacing must be positive, the origin finite");
  }
  if (heights_.size() != static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows)) {
    throw std::invalid_argument("ElevationGrid: cols × rows heights expected");
  }
  for (const double h : heights_) {
    if (!std::isfinite(h)) throw std::invalid_argument("ElevationGrid: a height is not finite");
  }
  const auto [lo, hi] = std::minmax_element(heights_.begin(), heights_.end());
  min_ = *lo;
  max_ = *hi;
}

double ElevationGrid::Height(double x, double y) const {
  const double gx = std::clamp((x - first_.x()) / spacing_.x(), 0.0, cols_ - 1.0);
  const double gy = std::clamp((y - first_.y()) / spacing_.y(), 0.0, rows_ - 1.0);
  const int c = std::min(static_cast<int>(gx), cols_ - 2);
  const int r = std::min(static_cast<int>(gy), rows_ - 2);
  const double u = gx - c, v = gy - r;
  const double bottom = Sample(c, r) + u * (Sample(c + 1, r) - Sample(c, r));
  const double top = Sample(c, r + 1) + u * (Sample(c + 1, r + 1) - Sample(c, r + 1));
  return bottom + v * (top - bottom);
}

bool ElevationGrid::Covers(double x_min, double y_min, double x_max, double y_max) const {
  const Eigen::Vector2d last = last_m();
  return x_min >= first_.x() && y_min >= first_.y() && x_max <= last.x() && y_max <= last.y();
}

}  // namespace trackbed::sim
