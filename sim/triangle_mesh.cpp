// Triangle meshes in the object's frame and placed in the world (see triangle_mesh.h).
#include "trackbed/sim/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace trackbed::sim {

Eigen::AlignedBox3d TriangleMesh::Bounds() const {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3f& v : vertices) box.extend(v.cast<double>());
  return box;
}

Eigen::Matrix3d RollPitchYaw(double roll_rad, double pitch_rad, double yaw_rad) {
  return (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

namespace {

// Cells in the plan grid at most; a triangle is listed in every cell its box meets.
constexpr double kMaxCells = 1 << 20;

double PointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Separating-axis test over both convex polygons' edge normals: the largest gap along
// any axis (negative: the smallest overlap when no axis separates them). Edges of no
// length give no axis (a vertical triangle is a segment in plan).
template <class A, class B>
double LargestAxisGap(const A& a, const B& b) {
  double best = -std::numeric_limits<double>::infinity();
  const auto span = [](const auto& poly, const Eigen::Vector2d& axis, double* lo, double* hi) {
    *lo = std::numeric_limits<double>::infinity();
    *hi = -*lo;
    for (const Eigen::Vector2d& p : poly) {
      *lo = std::min(*lo, p.dot(axis));
      *hi = std::max(*hi, p.dot(axis));
    }
  };
  const auto try_edges = [&](const auto& poly) {
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Eigen::Vector2d edge = poly[(k + 1) % poly.size()] - poly[k];
      const double len = edge.norm();
      if (!(len > 1e-12)) continue;
      const Eigen::Vector2d axis(-edge.y() / len, edge.x() / len);
      double a_lo, a_hi, b_lo, b_hi;
      span(a, axis, &a_lo, &a_hi);
      span(b, axis, &b_lo, &b_hi);
      best = std::max(best, std::max(b_lo - a_hi, a_lo - b_hi));
    }
  };
  try_edges(a);
  try_edges(b);
  return best;
}

// Signed distance between two convex polygons in plan (as LargestAxisGap when they
// overlap).
template <class A, class B>
double ConvexDistance(const A& a, const B& b) {
  const double gap = LargestAxisGap(a, b);
  if (gap <= 0.0) return gap;
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      d = std::min(d, PointSegmentDistance(a[i], b[j], b[(j + 1) % b.size()]));
    }
  }
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (std::size_t j = 0; j < a.size(); ++j) {
      d = std::min(d, PointSegmentDistance(b[i], a[j], a[(j + 1) % a.size()]));
    }
  }
  return d;
}

}  // namespace

PlacedMesh::PlacedMesh(const TriangleMesh& mesh, const Eigen::Vector3d& scale,
                       const Eigen::Isometry3d& pose)
    : triangles_(mesh.triangles) {
  vertices_.reserve(mesh.vertices.size());
  for (const Eigen::Vector3f& v : mesh.vertices) {
    vertices_.push_back(pose * Eigen::Vector3d(v.cast<double>().cwiseProduct(scale)));
    bounds_.extend(vertices_.back());
  }
  if (triangles_.empty() || bounds_.isEmpty()) return;
  // Cells about twice a triangle's mean plan size, at most kMaxCells of them.
  const Eigen::Vector2d size = bounds_.sizes().head<2>();
  const double per_triangle =
      std::sqrt(std::max(size.x() * size.y(), 0.0) / static_cast<double>(triangles_.size()));
  cell_m_ =
      std::max({2.0 * per_triangle, std::max(size.x(), size.y()) / std::sqrt(kMaxCells), 1e-3});
  first_ = bounds_.min().head<2>();
  cols_ = static_cast<int>(size.x() / cell_m_) + 1;
  rows_ = static_cast<int>(size.y() / cell_m_) + 1;
  // Counted, then filled: each cell's triangles contiguous.
  std::vector<std::uint32_t> count(static_cast<std::size_t>(cols_) * rows_ + 1, 0);
  const auto each_cell = [&](std::uint32_t t, auto&& visit) {
    Eigen::AlignedBox2d box;
    for (std::uint32_t v : triangles_[t]) box.extend(vertices_[v].head<2>());
    int c0, r0, c1, r1;
    CellsOf(box, &c0, &r0, &c1, &r1);
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) visit(static_cast<std::size_t>(r) * cols_ + c);
    }
  };
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
    each_cell(t, [&](std::size_t cell) { ++count[cell + 1]; });
  }
  for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
  cell_start_ = count;
  cell_triangles_.resize(count.back());
  cell_z_lo_.assign(count.size() - 1, std::numeric_limits<double>::infinity());
  cell_z_hi_.assign(count.size() - 1, -std::numeric_limits<double>::infinity());
  for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::uint32_t v : triangles_[t]) {
      lo = std::min(lo, vertices_[v].z());
      hi = std::max(hi, vertices_[v].z());
    }
    each_cell(t, [&](std::size_t cell) {
      cell_triangles_[count[cell]++] = t;
      cell_z_lo_[cell] = std::min(cell_z_lo_[cell], lo);
      cell_z_hi_[cell] = std::max(cell_z_hi_[cell], hi);
    });
  }
}

void PlacedMesh::CellsOf(const Eigen::AlignedBox2d& box, int* c0, int* r0, int* c1, int* r1) const {
  const auto index = [&](double v, double v0, int n) {
    return static_cast<int>(std::clamp(std::floor((v - v0) / cell_m_), 0.0, n - 1.0));
  };
  *c0 = index(box.min().x(), first_.x(), cols_);
  *c1 = index(box.max().x(), first_.x(), cols_);
  *r0 = index(box.min().y(), first_.y(), rows_);
  *r1 = index(box.max().y(), first_.y(), rows_);
}

std::optional<double> PlacedMesh::HighestAt(double x, double y) const {
  if (cell_start_.empty()) return std::nullopt;
  const Eigen::Vector2d p(x, y);
  if (!(x >= bounds_.min().x() && x <= bounds_.max().x() && y >= bounds_.min().y() &&
        y <= bounds_.max().y())) {
    return std::nullopt;
  }
  int c0, r0, c1, r1;
  CellsOf(Eigen::AlignedBox2d(p, p), &c0, &r0, &c1, &r1);
  const std::size_t cell = static_cast<std::size_t>(r0) * cols_ + c0;
  std::optional<double> highest;
  for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
    const auto& t = triangles_[cell_triangles_[k]];
    const Eigen::Vector3d &a = vertices_[t[0]], &b = vertices_[t[1]], &c = vertices_[t[2]];
    const Eigen::Vector2d ab = (b - a).head<2>(), ac = (c - a).head<2>(), ap = p - a.head<2>();
    const double det = ab.x() * ac.y() - ab.y() * ac.x();
    const double scale = ab.squaredNorm() + ac.squaredNorm();
    if (!(std::abs(det) > 1e-12 * scale)) continue;  // vertical: no height above a point
    const double u = (ap.x() * ac.y() - ap.y() * ac.x()) / det;
    const double v = (ab.x() * ap.y() - ab.y() * ap.x()) / det;
    constexpr double kEdge = -1e-12;  // points on an edge belong to both triangles
    if (u < kEdge || v < kEdge || u + v > 1.0 - kEdge) continue;
    const double z = a.z() + u * (b.z() - a.z()) + v * (c.z() - a.z());
    if (!highest || z > *highest) highest = z;
  }
  return highest;
}

double PlacedMesh::PlanDistance(const std::vector<Eigen::Vector2d>& polygon, double z_lo,
                                double z_hi) const {
  double best = std::numeric_limits<double>::infinity();
  if (cell_start_.empty() || polygon.empty()) return best;
  Eigen::AlignedBox2d around;
  for (const Eigen::Vector2d& p : polygon) around.extend(p);
  const Eigen::AlignedBox2d all(bounds_.min().head<2>(), bounds_.max().head<2>());
  std::array<Eigen::Vector2d, 3> plan;
  const auto visit = [&](int c, int r) {
    const std::size_t cell = static_cast<std::size_t>(r) * cols_ + c;
    if (cell_z_hi_[cell] < z_lo || cell_z_lo_[cell] > z_hi) return;
    for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
      const auto& t = triangles_[cell_triangles_[k]];
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d& v = vertices_[t[i]];
        lo = std::min(lo, v.z());
        hi = std::max(hi, v.z());
        plan[i] = v.head<2>();
      }
      if (hi < z_lo || lo > z_hi) continue;
      best = std::min(best, ConvexDistance(polygon, plan));
    }
  };
  // Rings of cells grown until the nearest triangle found lies within the searched
  // reach (any triangle not listed in the cells searched is farther); each ring visits
  // only the cells the last one did not (a triangle in several cells is measured again).
  int p_c0 = 0, p_r0 = 0, p_c1 = -1, p_r1 = -1;  // the cells searched so far
  for (double reach = cell_m_;; reach *= 2.0) {
    Eigen::AlignedBox2d box = around;
    box.min().array() -= reach;
    box.max().array() += reach;
    if (box.intersects(all)) {
      int c0, r0, c1, r1;
      CellsOf(box, &c0, &r0, &c1, &r1);
      for (int r = r0; r <= r1; ++r) {
        if (r < p_r0 || r > p_r1) {
          for (int c = c0; c <= c1; ++c) visit(c, r);
        } else {
          for (int c = c0; c < p_c0; ++c) visit(c, r);
          for (int c = p_c1 + 1; c <= c1; ++c) visit(c, r);
        }
      }
      p_c0 = c0, p_r0 = r0, p_c1 = c1, p_r1 = r1;
    }
    if (best <= reach || box.contains(all)) return best;
  }
}

}  // namespace trackbed::sim
