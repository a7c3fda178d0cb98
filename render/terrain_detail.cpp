// Levels of detail of the rendered terrain (see terrain_detail.h).
#include "trackbed/render/terrain_detail.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace trackbed::render {

TerrainDetail::TerrainDetail(const sim::Terrain& terrain, double full_detail_m, int chunk_cells,
                             std::optional<GridWindow> window)
    : terrain_(terrain),
      full_detail_m_(full_detail_m),
      window_(window.value_or(GridWindow::Whole(terrain))),
      cols_(window_.i1 - window_.i0 + 1),
      rows_(window_.j1 - window_.j0 + 1) {
  if (chunk_cells <= 0 || chunk_cells % (1 << kMaxLevel) != 0) {
    throw std::invalid_argument("TerrainDetail: chunk_cells must be a positive multiple of " +
                                std::to_string(1 << kMaxLevel) + " (got " +
                                std::to_string(chunk_cells) + ")");
  }
  const GridWindow& w = window_;
  const auto aligned = [&](int v, int edge) { return v == edge || v % chunk_cells == 0; };
  if (!(w.i0 >= 0 && w.j0 >= 0 && w.i1 < terrain.cols() && w.j1 < terrain.rows() && w.i1 > w.i0 &&
        w.j1 > w.j0 && aligned(w.i0, 0) && aligned(w.j0, 0) && aligned(w.i1, terrain.cols() - 1) &&
        aligned(w.j1, terrain.rows() - 1))) {
    throw std::invalid_argument(
        "TerrainDetail: the window is not a chunk-aligned part of the grid");
  }
  if (static_cast<double>(cols_ - 1) * (rows_ - 1) > kMaxCells) {
    throw std::invalid_argument("TerrainDetail: the window has more than 16 million cells");
  }
  BuildLevels(terrain);
  BuildChunks(terrain, chunk_cells);
}

// Every level's height and normal at the window's vertices.
void TerrainDetail::BuildLevels(const sim::Terrain& terrain) {
  const double cell = terrain.cell_size_m();
  // The grid's heights over the window and the border the coarsest level's
  // normals reach into, indices clamped to the grid: the corners of the coarse
  // cells that overhang the grid's far edges.
  const int border = 2 << kMaxLevel;
  const int bi0 = window_.i0 - border, bj0 = window_.j0 - border;
  const int bcols = cols_ + 2 * border, brows = rows_ + 2 * border;
  std::vector<double> h(static_cast<std::size_t>(bcols) * brows);
  for (int b = 0; b < brows; ++b) {
    for (int a = 0; a < bcols; ++a) {
      h[static_cast<std::size_t>(b) * bcols + a] = terrain.GridHeight(
          std::clamp(bi0 + a, 0, terrain.cols() - 1), std::clamp(bj0 + b, 0, terrain.rows() - 1));
    }
  }
  auto H = [&](int i, int j) { return h[static_cast<std::size_t>(j - bj0) * bcols + (i - bi0)]; };
  const std::size_t n = static_cast<std::size_t>(cols_) * rows_;
  for (int k = 0; k <= kMaxLevel; ++k) {
    const int s = 1 << k;
    std::vector<float>& z = z_[k];
    std::vector<Eigen::Vector3f>& nrm = n_[k];
    z.resize(n);
    nrm.resize(n);
    // Smooth normal at a level-k grid vertex from central differences at its spacing.
    auto corner_normal = [&](int I, int J) {
      const double nx = -(H(I + s, J) - H(I - s, J)) / (2 * s * cell);
      const double ny = -(H(I, J + s) - H(I, J - s)) / (2 * s * cell);
      return Eigen::Vector3d(nx, ny, 1.0).normalized();
    };
    for (int j = window_.j0; j <= window_.j1; ++j) {
      for (int i = window_.i0; i <= window_.i1; ++i) {
        const int I = i / s * s, J = j / s * s;
        const double u = static_cast<double>(i - I) / s, v = static_cast<double>(j - J) / s;
        // Barycentric weights in the coarse cell split along (I, J)–(I+s, J+s).
        double w00, wa, w11;
        int ai, aj;
        if (u >= v) {
          w00 = 1 - u, wa = u - v, w11 = v, ai = I + s, aj = J;
        } else {
          w00 = 1 - v, wa = v - u, w11 = u, ai = I, aj = J + s;
        }
        const double zz = w00 * H(I, J) + wa * H(ai, aj) + w11 * H(I + s, J + s);
        const Eigen::Vector3d nn = (w00 * corner_normal(I, J) + wa * corner_normal(ai, aj) +
                                    w11 * corner_normal(I + s, J + s))
                                       .normalized();
        z[Index(i, j)] = static_cast<float>(k == 0 ? H(i, j) : zz);
        nrm[Index(i, j)] = nn.cast<float>();
      }
    }
  }
}

// The window's chunks (one per material in each square) and their neighbours.
void TerrainDetail::BuildChunks(const sim::Terrain& terrain, int chunk_cells) {
  const double cell = terrain.cell_size_m();
  for (int j0 = window_.j0; j0 < window_.j1; j0 += chunk_cells) {
    for (int i0 = window_.i0; i0 < window_.i1; i0 += chunk_cells) {
      const int i1 = std::min(i0 + chunk_cells, window_.i1),
                j1 = std::min(j0 + chunk_cells, window_.j1);
      std::vector<bool> present(terrain.materials().size(), false);
      for (int j = j0; j < j1; ++j) {
        for (int i = i0; i < i1; ++i) present[terrain.CellMaterial(i, j)] = true;
      }
      const int kinds = static_cast<int>(std::count(present.begin(), present.end(), true));
      int max_level = 0;
      if (kinds == 1) {
        while (max_level < kMaxLevel && (i1 - i0) % (2 << max_level) == 0 &&
               (j1 - j0) % (2 << max_level) == 0) {
          ++max_level;
        }
      }
      float lo = 1e30f, hi = -1e30f;
      for (int k = 0; k <= kMaxLevel; ++k) {
        for (int j = j0; j <= j1; ++j) {
          for (int i = i0; i <= i1; ++i) {
            lo = std::min(lo, z_[k][Index(i, j)]);
            hi = std::max(hi, z_[k][Index(i, j)]);
          }
        }
      }
      const Eigen::AlignedBox3d box(
          Eigen::Vector3d(terrain.x_min() + i0 * cell, terrain.y_min() + j0 * cell, lo),
          Eigen::Vector3d(terrain.x_min() + i1 * cell, terrain.y_min() + j1 * cell, hi));
      for (std::size_t m = 0; m < present.size(); ++m) {
        if (present[m]) chunks_.push_back({i0, j0, i1, j1, static_cast<int>(m), max_level, box});
      }
    }
  }
  for (Chunk& c : chunks_) {
    for (std::size_t o = 0; o < chunks_.size(); ++o) {
      const Chunk& other = chunks_[o];
      const int k = static_cast<int>(o);
      if (other.j0 == c.j0 && other.i1 == c.i0) c.neighbor[0] = k;
      if (other.j0 == c.j0 && other.i0 == c.i1) c.neighbor[1] = k;
      if (other.i0 == c.i0 && other.j1 == c.j0) c.neighbor[2] = k;
      if (other.i0 == c.i0 && other.j0 == c.j1) c.neighbor[3] = k;
    }
  }
}

double TerrainDetail::LevelAt(double distance_m) const {
  if (!(full_detail_m_ > 0.0)) return 0.0;
  double start = full_detail_m_;
  for (int k = 0; k < kMaxLevel; ++k, start *= 2.0) {
    if (distance_m < start) return k;
    if (distance_m < 1.5 * start) return k + (distance_m - start) / (0.5 * start);
  }
  return kMaxLevel;
}

void TerrainDetail::DistanceRange(const Chunk& c, const Eigen::Vector2d& p, double* d_min,
                                  double* d_max) const {
  const Eigen::Vector2d lo = c.box.min().head<2>(), hi = c.box.max().head<2>();
  const Eigen::Vector2d nearest = p.cwiseMax(lo).cwiseMin(hi);
  *d_min = (p - nearest).norm();
  const Eigen::Vector2d far((p.x() - lo.x() > hi.x() - p.x()) ? lo.x() : hi.x(),
                            (p.y() - lo.y() > hi.y() - p.y()) ? lo.y() : hi.y());
  *d_max = (p - far).norm();
}

int TerrainDetail::MeshLevel(const Chunk& c, const Eigen::Vector2d& center_xy) const {
  double d_min, d_max;
  DistanceRange(c, center_xy, &d_min, &d_max);
  // Every vertex is at least at the blend level of the nearest point.
  return std::min(c.max_level, static_cast<int>(std::floor(LevelAt(d_min))));
}

bool TerrainDetail::SameMesh(const Chunk& c, const Eigen::Vector2d& a_xy,
                             const Eigen::Vector2d& b_xy) const {
  double a_min, a_max, b_min, b_max;
  DistanceRange(c, a_xy, &a_min, &a_max);
  DistanceRange(c, b_xy, &b_min, &b_max);
  // The blend is one whole level over the chunk, the same from both centres.
  const double level = LevelAt(a_min);
  if (!(level == std::floor(level) && LevelAt(a_max) == level && LevelAt(b_min) == level &&
        LevelAt(b_max) == level)) {
    return false;
  }
  // ... and its sides go on the same neighbours' edges.
  for (int n : c.neighbor) {
    if (n < 0) continue;
    const Chunk& other = chunks_[static_cast<std::size_t>(n)];
    if (MeshLevel(other, a_xy) != MeshLevel(other, b_xy)) return false;
  }
  return true;
}

double TerrainDetail::Height(int i, int j, double level) const {
  const int k = static_cast<int>(std::floor(level));
  if (k >= kMaxLevel) return z_[kMaxLevel][Index(i, j)];
  const double f = level - k;
  const float a = z_[k][Index(i, j)];
  return f == 0.0 ? a : a + f * (z_[k + 1][Index(i, j)] - a);
}

namespace {

// Vertex `v` put the fraction `f` of the way from `p0` to `p1` on their edge (height
// and normal; its x, y and texture coordinates are its own). Both chunks of a seam
// make their seam vertices here, so they get the same bits.
void PutOnEdge(const TerrainVertex& p0, const TerrainVertex& p1, float f, TerrainVertex* v) {
  v->z = p0.z + f * (p1.z - p0.z);
  const Eigen::Vector3f n =
      ((1 - f) * Eigen::Vector3f(p0.nx, p0.ny, p0.nz) + f * Eigen::Vector3f(p1.nx, p1.ny, p1.nz))
          .normalized();
  v->nx = n.x(), v->ny = n.y(), v->nz = n.z();
}

// Side `side` of a mesh of na × nb cells (i = i0, i = i1, j = j0, j = j1): how many
// cells it has and the index of its q-th vertex.
struct MeshSide {
  MeshSide(int side, int na, int nb)
      : along_j(side < 2),
        fixed(side == 0 || side == 2 ? 0 : (side < 2 ? na : nb)),
        cells(side < 2 ? nb : na),
        row(na + 1) {}
  std::size_t Vertex(int q) const {
    return static_cast<std::size_t>(along_j ? q * row + fixed : fixed * row + q);
  }
  bool along_j;  // sides i = i0 and i = i1 run along j
  int fixed;     // the side's column (along j) or row
  int cells;
  int row;  // vertices per row
};

// Triangles fanned from `apex` to each two consecutive vertices of `path`.
void Fan(std::uint32_t apex, const std::vector<std::uint32_t>& path,
         std::vector<std::uint32_t>* indices) {
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    indices->insert(indices->end(), {path[k], path[k + 1], apex});
  }
}

// Triangle `corner` (counter-clockwise) with `between[k]` the vertices on its edge
// from corner k to corner k + 1, in that order. At most two edges hold vertices, and
// then two consecutive ones.
void AddTriangle(const std::array<std::uint32_t, 3>& corner,
                 const std::array<std::vector<std::uint32_t>, 3>& between,
                 std::vector<std::uint32_t>* indices) {
  int first = -1, count = 0;
  for (int k = 2; k >= 0; --k) {
    if (between[k].empty()) continue;
    ++count;
    if (first < 0 || !between[(k + 1) % 3].empty()) first = k;
  }
  const auto path = [&](int k, bool to_end) {
    std::vector<std::uint32_t> p{corner[k]};
    p.insert(p.end(), between[k].begin(), between[k].end());
    if (to_end) p.push_back(corner[(k + 1) % 3]);
    return p;
  };
  if (count == 0) {
    indices->insert(indices->end(), corner.begin(), corner.end());
  } else if (count == 1) {
    Fan(corner[(first + 2) % 3], path(first, true), indices);
  } else {
    // Edges A→C and C→B: A→C's pieces fanned from B, then C→B's from the last vertex
    // before C (not on C→B, so no triangle is flat).
    const std::vector<std::uint32_t> a_to_c = path(first, false);
    Fan(corner[(first + 2) % 3], a_to_c, indices);
    Fan(a_to_c.back(), path((first + 1) % 3, true), indices);
  }
}

}  // namespace

TerrainVertex TerrainDetail::BlendedVertex(int i, int j, const Eigen::Vector2d& center_xy,
                                           double meters_per_repeat) const {
  const double cell = terrain_.cell_size_m();
  const double x = terrain_.x_min() + i * cell, y = terrain_.y_min() + j * cell;
  const double g = LevelAt(std::hypot(x - center_xy.x(), y - center_xy.y()));
  const int k = std::min(static_cast<int>(std::floor(g)), kMaxLevel);
  const float f = static_cast<float>(g - k);
  Eigen::Vector3f normal = n_[k][Index(i, j)];
  if (f > 0.0f) normal = ((1.0f - f) * normal + f * n_[k + 1][Index(i, j)]).normalized();
  return {static_cast<float>(x),
          static_cast<float>(y),
          static_cast<float>(Height(i, j, g)),
          normal.x(),
          normal.y(),
          normal.z(),
          static_cast<float>(x / meters_per_repeat),
          static_cast<float>(y / meters_per_repeat)};
}

// The mesh level of the chunk across each side (-1 where there is none).
std::array<int, 4> TerrainDetail::SideLevels(const Chunk& c,
                                             const Eigen::Vector2d& center_xy) const {
  std::array<int, 4> level{-1, -1, -1, -1};
  for (int side = 0; side < 4; ++side) {
    if (c.neighbor[side] < 0) continue;
    level[side] = MeshLevel(chunks_[static_cast<std::size_t>(c.neighbor[side])], center_xy);
  }
  return level;
}

// Along a side shared with a coarser neighbour, the vertices between the
// neighbour's go on its edge: interpolated between the two around them.
void TerrainDetail::PutSidesOnCoarserEdges(const Chunk& c, int level,
                                           const std::array<int, 4>& side_level, Mesh* mesh) const {
  const int s = 1 << level;
  const int na = (c.i1 - c.i0) / s, nb = (c.j1 - c.j0) / s;
  for (int side = 0; side < 4; ++side) {
    if (side_level[side] <= level) continue;
    const int step = 1 << (side_level[side] - level);
    const MeshSide edge(side, na, nb);
    const auto at = [&](int q) -> TerrainVertex& { return mesh->vertices[edge.Vertex(q)]; };
    for (int q = 0; q < edge.cells; q += step) {
      const TerrainVertex p0 = at(q), p1 = at(q + step);
      for (int r = 1; r < step; ++r) {
        PutOnEdge(p0, p1, static_cast<float>(r) / step, &at(q + r));
      }
    }
  }
}

// Along a side shared with a finer neighbour, the neighbour's vertices between the
// mesh's, made as the neighbour makes them, appended to the mesh.
std::array<TerrainDetail::SideVertices, 4> TerrainDetail::AddFinerSideVertices(
    const Chunk& c, int level, const std::array<int, 4>& side_level,
    const Eigen::Vector2d& center_xy, double meters_per_repeat, Mesh* mesh) const {
  const int s = 1 << level;
  const int na = (c.i1 - c.i0) / s, nb = (c.j1 - c.j0) / s;
  std::array<SideVertices, 4> sides;
  for (int side = 0; side < 4; ++side) {
    if (side_level[side] < 0 || side_level[side] >= level) continue;
    const int step = 1 << (level - side_level[side]), fine = s / step;
    const MeshSide edge(side, na, nb);
    sides[side] = {static_cast<std::uint32_t>(mesh->vertices.size()), step - 1};
    for (int q = 0; q < edge.cells; ++q) {
      const TerrainVertex p0 = mesh->vertices[edge.Vertex(q)];
      const TerrainVertex p1 = mesh->vertices[edge.Vertex(q + 1)];
      const int a = edge.along_j ? edge.fixed : q, b = edge.along_j ? q : edge.fixed;
      const int da = edge.along_j ? 0 : 1, db = 1 - da;
      for (int r = 1; r < step; ++r) {
        TerrainVertex v = BlendedVertex(c.i0 + a * s + da * r * fine, c.j0 + b * s + db * r * fine,
                                        center_xy, meters_per_repeat);
        PutOnEdge(p0, p1, static_cast<float>(r) / step, &v);
        mesh->vertices.push_back(v);
      }
    }
  }
  return sides;
}

// Two triangles per cell, split along (a, b)–(a+1, b+1) as Terrain and Bullet split
// it; a cell on a side with a finer neighbour fans its edge to the neighbour's vertices.
void TerrainDetail::Triangulate(const Chunk& c, int level, const std::array<SideVertices, 4>& sides,
                                Mesh* mesh) const {
  const int s = 1 << level;
  const int na = (c.i1 - c.i0) / s, nb = (c.j1 - c.j0) / s;
  const auto v = [&](int a, int b) { return static_cast<std::uint32_t>(b * (na + 1) + a); };
  // The vertices a finer neighbour puts on `side` between the mesh's q and q + 1.
  const auto between = [&](int side, int q, bool growing) {
    std::vector<std::uint32_t> out;
    const SideVertices& sv = sides[side];
    for (int r = 0; r < sv.per_cell; ++r) {
      out.push_back(sv.first + static_cast<std::uint32_t>(q * sv.per_cell + r));
    }
    if (!growing) std::reverse(out.begin(), out.end());
    return out;
  };
  std::vector<std::uint32_t>& idx = mesh->indices;
  for (int b = 0; b < nb; ++b) {
    for (int a = 0; a < na; ++a) {
      if (level == 0 && terrain_.CellMaterial(c.i0 + a, c.j0 + b) != c.material) continue;
      const bool bottom = b == 0 && sides[2].per_cell > 0,
                 right = a == na - 1 && sides[1].per_cell > 0;
      const bool top = b == nb - 1 && sides[3].per_cell > 0, left = a == 0 && sides[0].per_cell > 0;
      if (bottom || right) {
        AddTriangle({v(a, b), v(a + 1, b), v(a + 1, b + 1)},
                    {bottom ? between(2, a, true) : std::vector<std::uint32_t>{},
                     right ? between(1, b, true) : std::vector<std::uint32_t>{},
                     {}},
                    &idx);
      } else {
        idx.insert(idx.end(), {v(a, b), v(a + 1, b), v(a + 1, b + 1)});
      }
      if (top || left) {
        AddTriangle({v(a, b), v(a + 1, b + 1), v(a, b + 1)},
                    {std::vector<std::uint32_t>{},
                     top ? between(3, a, false) : std::vector<std::uint32_t>{},
                     left ? between(0, b, false) : std::vector<std::uint32_t>{}},
                    &idx);
      } else {
        idx.insert(idx.end(), {v(a, b), v(a + 1, b + 1), v(a, b + 1)});
      }
    }
  }
}

void TerrainDetail::BuildMesh(const Chunk& c, const Eigen::Vector2d& center_xy,
                              double meters_per_repeat, Mesh* mesh) const {
  const int level = MeshLevel(c, center_xy);
  const int s = 1 << level;
  const int na = (c.i1 - c.i0) / s, nb = (c.j1 - c.j0) / s;
  mesh->vertices.clear();
  for (int b = 0; b <= nb; ++b) {
    for (int a = 0; a <= na; ++a) {
      mesh->vertices.push_back(
          BlendedVertex(c.i0 + a * s, c.j0 + b * s, center_xy, meters_per_repeat));
    }
  }
  const std::array<int, 4> side_level = SideLevels(c, center_xy);
  PutSidesOnCoarserEdges(c, level, side_level, mesh);
  const std::array<SideVertices, 4> sides =
      AddFinerSideVertices(c, level, side_level, center_xy, meters_per_repeat, mesh);
  int topology = level;
  for (const SideVertices& side : sides) topology = topology * 8 + side.per_cell;
  if (mesh->chunk == &c && mesh->topology == topology) return;  // same triangles
  mesh->chunk = &c;
  mesh->level = level;
  mesh->topology = topology;
  mesh->indices.clear();
  Triangulate(c, level, sides, mesh);
}

}  // namespace trackbed::render
