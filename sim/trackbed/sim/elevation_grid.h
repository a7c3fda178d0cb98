// ElevationGrid: heights on a regular grid of sample points — a digital elevation
// model's pixels, already in the world frame — and the surface between them.
//
// The surface between four sample points is bilinear in them: the project's own
// interpolation, so that a terrain's heights do not depend on the version of the
// library that read the file (assets/trackbed/assets/dem_reader.h reads it).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace trackbed::sim {

class ElevationGrid {
 public:
  /// `heights_m` holds cols × rows heights [m], x fastest, the first row at the lowest
  /// y: sample (c, r) lies at first_m + (c · spacing_m.x(), r · spacing_m.y()).
  /// Throws std::invalid_argument unless cols, rows >= 2, the spacing is positive and
  /// every height finite.
  ElevationGrid(int cols, int rows, const Eigen::Vector2d& first_m,
                const Eigen::Vector2d& spacing_m, std::vector<double> heights_m);

  /// Height at (x, y) [m], bilinear in the four samples around it; beyond the samples'
  /// rectangle the nearest edge's (Covers says where the grid is defined).
  double Height(double x, double y) const;
  /// Whether the samples' rectangle holds the axis-aligned box [x_min, x_max] × [y_min, y_max].
  bool Covers(double x_min, double y_min, double x_max, double y_max) const;
  /// Height of sample (c, r) [m].
  double Sample(int c, int r) const {
    return heights_[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) +
                    static_cast<std::size_t>(c)];
  }

  int cols() const { return cols_; }
  int rows() const { return rows_; }
  const Eigen::Vector2d& first_m() const { return first_; }      ///< Sample (0, 0) [m].
  const Eigen::Vector2d& spacing_m() const { return spacing_; }  ///< Between samples [m].
  Eigen::Vector2d last_m() const {  ///< Sample (cols − 1, rows − 1) [m].
    return first_ + Eigen::Vector2d((cols_ - 1) * spacing_.x(), (rows_ - 1) * spacing_.y());
  }
  double min_height_m() const { return min_; }  ///< Lowest sample [m].
  double max_height_m() const { return max_; }  ///< Highest sample [m].

 private:
  int cols_, rows_;
  Eigen::Vector2d first_, spacing_;
  std::vector<double> heights_;
  double min_ = 0.0, max_ = 0.0;
};

}  // namespace trackbed::sim
