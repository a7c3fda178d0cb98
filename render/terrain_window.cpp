// The renderer's window of a large terrain (see terrain_window.h).
#include "trackbed/render/terrain_window.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace trackbed::render {

TerrainWindow::TerrainWindow(const sim::Terrain& terrain, double full_detail_m)
    : terrain_(terrain) {
  const double coarsest_m = 1.5 * (1 << (TerrainDetail::kMaxLevel - 1)) * full_detail_m;
  const int reach = static_cast<int>(std::ceil(std::max(coarsest_m, 12.0) / terrain.cell_size_m()));
  half_cells_ = (reach + 2 * kSnapCells + kSnapCells - 1) / kSnapCells * kSnapCells;
  paged_ = full_detail_m > 0.0 &&
           (terrain.cols() - 1 > 2 * half_cells_ || terrain.rows() - 1 > 2 * half_cells_);
}

std::optional<TerrainWindow::Placement> TerrainWindow::Follow(
    const Eigen::Vector2d& center_xy, const std::optional<Placement>& current) const {
  if (!paged_) {
    if (current) return std::nullopt;
    return Placement{GridWindow::Whole(terrain_), 0, 0};
  }
  const double c = terrain_.cell_size_m();
  const auto cell = [&](double v, double v0, int n) {
    return std::clamp(static_cast<int>(std::floor((v - v0) / c)), 0, n - 1);
  };
  const int ci = cell(center_xy.x(), terrain_.x_min(), terrain_.cols());
  const int cj = cell(center_xy.y(), terrain_.y_min(), terrain_.rows());
  if (current && std::abs(ci - current->center_i) <= kSnapCells &&
      std::abs(cj - current->center_j) <= kSnapCells) {
    return std::nullopt;
  }
  Placement p;
  p.center_i = (ci + kSnapCells / 2) / kSnapCells * kSnapCells;
  p.center_j = (cj + kSnapCells / 2) / kSnapCells * kSnapCells;
  p.window = {std::max(p.center_i - half_cells_, 0), std::max(p.center_j - half_cells_, 0),
              std::min(p.center_i + half_cells_, terrain_.cols() - 1),
              std::min(p.center_j + half_cells_, terrain_.rows() - 1)};
  if (current && p.window == current->window) return std::nullopt;
  return p;
}

}  // namespace trackbed::render
