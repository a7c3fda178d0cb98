// Range scan → obstacle circles (see scan_clustering.h).
#include "trackbed/navigation/scan_clustering.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include <Eigen/Dense>

#include "trackbed/common/option_error.h"

namespace trackbed::navigation {
namespace {

using Points = std::vector<Eigen::Vector2d>;

Eigen::Vector2d Mean(const Points& points) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

double CoveringRadius(const Eigen::Vector2d& centre, const Points& points, double at_least) {
  double r = at_least;
  for (const Eigen::Vector2d& p : points) r = std::max(r, (p - centre).norm());
  return r;
}

double Extent(const Points& points) {
  double e = 0.0;
  for (const Eigen::Vector2d& p : points) e = std::max(e, (p - points.front()).norm());
  return e;
}

// Kåsa's algebraic fit: x² + y² + D x + E y + F = 0 in the least-squares sense, solved
// about the points' mean for conditioning. Empty if degenerate (collinear hits).
std::optional<Circle> KasaFit(const Points& points) {
  const Eigen::Vector2d mean = Mean(points);
  Eigen::MatrixXd A(points.size(), 3);
  Eigen::VectorXd b(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d q = points[i] - mean;
    A(i, 0) = q.x();
    A(i, 1) = q.y();
    A(i, 2) = 1.0;
    b(i) = -q.squaredNorm();
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  if (!(s(2) > 1e-9 * s(0))) return std::nullopt;
  const Eigen::Vector3d x = svd.solve(b);
  const Eigen::Vector2d centre(-x(0) / 2.0, -x(1) / 2.0);
  const double r2 = centre.squaredNorm() - x(2);
  if (!(r2 > 0.0)) return std::nullopt;
  return Circle{mean + centre, std::sqrt(r2)};
}

Circle FitCluster(const Points& points, const Eigen::Vector2d& sensor,
                  const ScanClusteringOptions& options) {
  const Eigen::Vector2d mean = Mean(points);
  const double extent = Extent(points);
  if (static_cast<int>(points.size()) >= options.min_fit_points) {
    if (const std::optional<Circle> fit = KasaFit(points)) {
      const bool beyond = (fit->centre - sensor).norm() > (mean - sensor).norm();
      if (beyond && fit->radius_m >= options.min_radius_m &&
          fit->radius_m <= options.max_radius_m) {
        return {fit->centre, CoveringRadius(fit->centre, points, fit->radius_m)};
      }
    }
  }
  const double r = std::max(options.min_radius_m, extent / 2.0);
  const Eigen::Vector2d away = (mean - sensor).norm() > 0.0
                                   ? Eigen::Vector2d((mean - sensor).normalized())
                                   : Eigen::Vector2d::UnitX();
  const Eigen::Vector2d centre = mean + r * away;
  return {centre, CoveringRadius(centre, points, r)};
}

void EmitCluster(const Points& points, const Eigen::Vector2d& sensor,
                 const ScanClusteringOptions& options, std::vector<Circle>* out) {
  if (static_cast<int>(points.size()) < options.min_cluster_points || points.empty()) return;
  if (Extent(points) <= options.max_fit_extent_m) {
    out->push_back(FitCluster(points, sensor, options));
    return;
  }
  // A wall: consecutive pieces no longer than half the spacing, each covered by a circle.
  std::vector<Circle> chain;
  Points piece;
  auto close_piece = [&]() {
    const Eigen::Vector2d c = Mean(piece);
    chain.push_back({c, CoveringRadius(c, piece, options.min_radius_m)});
    piece.clear();
  };
  for (const Eigen::Vector2d& p : points) {
    if (!piece.empty() && (p - piece.front()).norm() > options.wall_spacing_m / 2.0) close_piece();
    piece.push_back(p);
  }
  close_piece();
  // The cluster is continuous (no jump), so where two piece centres are still farther
  // apart than the spacing the wall runs between them: fill it in.
  out->push_back(chain.front());
  for (std::size_t k = 1; k < chain.size(); ++k) {
    const Eigen::Vector2d a = chain[k - 1].centre, b = chain[k].centre;
    const int gaps = static_cast<int>(std::ceil((b - a).norm() / options.wall_spacing_m - 1e-12));
    const double r = std::min(chain[k - 1].radius_m, chain[k].radius_m);
    for (int g = 1; g < gaps; ++g) {
      out->push_back({a + (b - a) * (static_cast<double>(g) / gaps), r});
    }
    out->push_back(chain[k]);
  }
}

}  // namespace

void ScanClusteringOptions::Validate() const {
  option_check::Positive("jump_threshold_m", jump_threshold_m);
  option_check::Positive("max_fit_extent_m", max_fit_extent_m);
  option_check::Positive("wall_spacing_m", wall_spacing_m);
  if (min_fit_points < 3) throw OptionError("min_fit_points", "must be >= 3");
  option_check::Positive("min_radius_m", min_radius_m);
  if (!(std::isfinite(max_radius_m) && max_radius_m >= min_radius_m)) {
    throw OptionError("max_radius_m",
                      "must be >= min_radius_m (got " + option_check::Describe(max_radius_m) + ")");
  }
  if (min_cluster_points < 1) throw OptionError("min_cluster_points", "must be >= 1");
}

std::vector<Circle> ClusterScan(const RangeScan& scan, const Pose2& sensor_pose_world,
                                const ScanClusteringOptions& options) {
  options.Validate();
  if (scan.ranges_m.size() != scan.angles_rad.size()) {
    throw std::invalid_argument("ClusterScan: " + std::to_string(scan.ranges_m.size()) +
                                " ranges but " + std::to_string(scan.angles_rad.size()) +
                                " beam angles");
  }
  const Eigen::Vector2d sensor(sensor_pose_world.x, sensor_pose_world.y);
  // Clusters of consecutive hits, in beam order.
  std::vector<Points> clusters;
  Points current;
  bool first_open = false;  // the first cluster starts at beam 0
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double r = scan.ranges_m[i];
    if (!(std::isfinite(r) && r > 0.0 && r < scan.max_range_m)) {
      if (!current.empty()) clusters.push_back(std::move(current));
      current.clear();
      continue;
    }
    const double a = sensor_pose_world.yaw + scan.angles_rad[i];
    const Eigen::Vector2d hit = sensor + r * Eigen::Vector2d(std::cos(a), std::sin(a));
    if (i == 0) first_open = true;
    if (!current.empty() && (hit - current.back()).norm() > options.jump_threshold_m) {
      clusters.push_back(std::move(current));
      current.clear();
    }
    current.push_back(hit);
  }
  const bool last_open = !current.empty() && !scan.ranges_m.empty() &&
                         std::isfinite(scan.ranges_m.back()) &&
                         scan.ranges_m.back() < scan.max_range_m;
  if (!current.empty()) clusters.push_back(std::move(current));
  if (options.wrap_around && first_open && last_open && clusters.size() >= 2 &&
      (clusters.front().front() - clusters.back().back()).norm() <= options.jump_threshold_m) {
    Points joined = std::move(clusters.back());
    joined.insert(joined.end(), clusters.front().begin(), clusters.front().end());
    clusters.pop_back();
    clusters.front() = std::move(joined);
  }
  std::vector<Circle> circles;
  for (const Points& cluster : clusters) EmitCluster(cluster, sensor, options, &circles);
  return circles;
}

}  // namespace trackbed::navigation
