// Which part of a large terrain's grid the renderer meshes in detail: a square
// window around the detail centre (the stereo rig), moved in steps as the robot
// drives, with the far terrain's coarse rings beyond it (trackbed/render/far_terrain.h).
//
// The window reaches at least as far as TerrainDetail blends to its coarsest level
// (1.5 · 2^(kMaxLevel−1) · full_detail_m, 12 m for the park's 2 m) and 12 m, plus
// the slack the centre may wander before the window moves and the snap of its centre
// to the grid: so beyond the window's edge the near ground is already at the
// coarsest level, which is exactly the far terrain's first ring. A terrain that fits
// in the window, or drawn at full detail everywhere (full_detail_m ≤ 0), is not
// paged: the window is the whole grid and never moves.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "trackbed/render/terrain_detail.h"
#include "trackbed/sim/terrain.h"

namespace trackbed::render {

class TerrainWindow {
 public:
  /// Grid cells the window's centre snaps to, and may wander before it moves.
  static constexpr int kSnapCells = 32;

  TerrainWindow(const sim::Terrain& terrain, double full_detail_m);

  /// True when the window moves with the centre (else it is the whole grid).
  bool paged() const { return paged_; }
  /// Half the window's side [cells], a multiple of kSnapCells.
  int half_cells() const { return half_cells_; }
  /// A window and the grid vertex it is centred on (before clipping to the grid).
  struct Placement {
    GridWindow window;
    int center_i = 0, center_j = 0;
  };
  /// Where the window goes for detail centre `center_xy` (world, m) when it must
  /// move from `current` (none: no window yet); nullopt when `current` still holds:
  /// the centre is within kSnapCells of its own, or moving gives the same window.
  std::optional<Placement> Follow(const Eigen::Vector2d& center_xy,
                                  const std::optional<Placement>& current) const;

 private:
  const sim::Terrain& terrain_;
  int half_cells_ = 0;
  bool paged_ = false;
};

}  // namespace trackbed::render
