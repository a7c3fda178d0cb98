// The far terrain's nested rings (see far_terrain.h).
#include "trackbed/render/far_terrain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace trackbed::render {
namespace {

int FloorTo(int v, int m) { return v >= 0 ? v / m * m : -((-v + m - 1) / m) * m; }
int CeilTo(int v, int m) { return -FloorTo(-v, m); }

// `inner` grown by `cells` on every side, outward to multiples of `multiple`, clipped
// to the grid.
GridWindow Grown(const GridWindow& inner, int cells, int multiple, const sim::Terrain& t) {
  return {std::max(FloorTo(inner.i0 - cells, multiple), 0),
          std::max(FloorTo(inner.j0 - cells, multiple), 0),
          std::min(CeilTo(inner.i1 + cells, multiple), t.cols() - 1),
          std::min(CeilTo(inner.j1 + cells, multiple), t.rows() - 1)};
}

// Smooth normal at grid vertex (i, j) from central differences at spacing s, as
// TerrainDetail gives its level's lattice vertices.
Eigen::Vector3d CornerNormal(const sim::Terrain& t, int i, int j, int s) {
  const auto H = [&](int a, int b) {
    return t.VertexHeight(std::clamp(a, 0, t.cols() - 1), std::clamp(b, 0, t.rows() - 1));
  };
  const double c = t.cell_size_m();
  const double nx = -(H(i + s, j) - H(i - s, j)) / (2 * s * c);
  const double ny = -(H(i, j + s) - H(i, j - s)) / (2 * s * c);
  // TerrainDetail normalizes the corner normal, then its blend (here of one corner).
  return Eigen::Vector3d(nx, ny, 1.0).normalized().normalized();
}

std::vector<int> Positions(int lo, int hi, int s) {
  std::vector<int> v;
  for (int p = lo; p < hi; p += s) v.push_back(p);
  v.push_back(hi);
  return v;
}

}  // namespace

// A ring's lattice: the positions along x and y (multiples of s, and the grid's
// edge where it cuts the last quad short), and the height and normal at each.
struct FarTerrain::RingLattice {
  std::vector<int> xs, ys;
  std::vector<double> z;
  std::vector<Eigen::Vector3d> n;
  std::size_t at(std::size_t a, std::size_t b) const { return b * xs.size() + a; }
};

FarTerrain::RingLattice FarTerrain::SampleRing(const sim::Terrain& terrain, const GridWindow& out,
                                               int s) {
  RingLattice r;
  r.xs = Positions(out.i0, out.i1, s);
  r.ys = Positions(out.j0, out.j1, s);
  r.z.resize(r.xs.size() * r.ys.size());
  r.n.resize(r.z.size());
  for (std::size_t b = 0; b < r.ys.size(); ++b) {
    for (std::size_t a = 0; a < r.xs.size(); ++a) {
      r.z[r.at(a, b)] = terrain.VertexHeight(r.xs[a], r.ys[b]);
      r.n[r.at(a, b)] = CornerNormal(terrain, r.xs[a], r.ys[b], s);
    }
  }
  return r;
}

// On the ring's outer edges that the next (twice as coarse) ring meets, puts every
// vertex between that ring's on the segment between them.
void FarTerrain::StitchOuterEdges(const sim::Terrain& terrain, const GridWindow& out, int s,
                                  RingLattice* r) {
  const std::size_t nx = r->xs.size(), ny = r->ys.size();
  // Along one edge: `count` vertices, the k-th at grid position pos[k] and lattice
  // index index(k). The coarser ring's vertices there are the multiples of 2s and
  // the grid's edge.
  const auto stitch = [&](std::size_t count, const std::vector<int>& pos, auto index) {
    for (std::size_t k = 1; k + 1 < count; ++k) {
      if (pos[k] % (2 * s) == 0) continue;
      const double f = static_cast<double>(pos[k] - pos[k - 1]) / (pos[k + 1] - pos[k - 1]);
      const std::size_t lo = index(k - 1), hi = index(k + 1);
      r->z[index(k)] = r->z[lo] + f * (r->z[hi] - r->z[lo]);
      r->n[index(k)] = ((1 - f) * r->n[lo] + f * r->n[hi]).normalized();
    }
  };
  if (out.j0 > 0) stitch(nx, r->xs, [&](std::size_t k) { return r->at(k, 0); });
  if (out.j1 < terrain.rows() - 1) {
    stitch(nx, r->xs, [&](std::size_t k) { return r->at(k, ny - 1); });
  }
  if (out.i0 > 0) stitch(ny, r->ys, [&](std::size_t k) { return r->at(0, k); });
  if (out.i1 < terrain.cols() - 1) {
    stitch(ny, r->ys, [&](std::size_t k) { return r->at(nx - 1, k); });
  }
}

FarTerrain::FarTerrain(const sim::Terrain& terrain, const GridWindow& inner, double reach_m,
                       const std::vector<double>& meters_per_repeat)
    : outer_(inner), meters_per_repeat_(meters_per_repeat) {
  if (meters_per_repeat.size() != terrain.materials().size()) {
    throw std::invalid_argument("FarTerrain: one repeat length per material");
  }
  const int reach = static_cast<int>(std::ceil(reach_m / terrain.cell_size_m()));
  const GridWindow goal = Grown(inner, reach, 1, terrain);
  const auto covers = [&](const GridWindow& w) {
    return w.i0 <= goal.i0 && w.j0 <= goal.j0 && w.i1 >= goal.i1 && w.j1 >= goal.j1;
  };
  for (int level = TerrainDetail::kMaxLevel; level <= kMaxLevel && !covers(outer_); ++level) {
    const int s = 1 << level;
    // Rings kRingQuads wide, their outer edge on the next ring's lattice; the last
    // reaches the goal (and holds the rings within).
    GridWindow out = Grown(outer_, kRingQuads * s, 2 * s, terrain);
    const bool last = level == kMaxLevel || covers(out);
    if (last) {
      out = Grown({std::min(goal.i0, outer_.i0), std::min(goal.j0, outer_.j0),
                   std::max(goal.i1, outer_.i1), std::max(goal.j1, outer_.j1)},
                  0, s, terrain);
    }
    RingLattice ring = SampleRing(terrain, out, s);
    if (!last) StitchOuterEdges(terrain, out, s, &ring);
    AddQuads(terrain, ring, outer_, s, level > TerrainDetail::kMaxLevel);
    if (level == TerrainDetail::kMaxLevel) AddSkirts(terrain, ring, outer_);
    outer_ = out;
    ++ring_;
  }
}

FarTerrain::Piece& FarTerrain::PieceFor(int block_a, int block_b, int material) {
  const auto key = std::make_tuple(ring_, block_a, block_b, material);
  auto it = piece_index_.find(key);
  if (it == piece_index_.end()) {
    it = piece_index_.emplace(key, pieces_.size()).first;
    pieces_.emplace_back();
    pieces_.back().material = material;
  }
  return pieces_[it->second];
}

void FarTerrain::AddVertex(Piece* p, double x, double y, double z, const Eigen::Vector3d& n,
                           double s_offset_m) {
  const double m = meters_per_repeat_[static_cast<std::size_t>(p->material)];
  p->vertices.push_back({static_cast<float>(x), static_cast<float>(y), static_cast<float>(z),
                         static_cast<float>(n.x()), static_cast<float>(n.y()),
                         static_cast<float>(n.z()), static_cast<float>((x + s_offset_m) / m),
                         static_cast<float>(y / m)});
  p->box.extend(Eigen::Vector3d(x, y, z));
}

// The ring's quads outside `in`, two triangles each along the (a, b)–(a+1, b+1)
// diagonal, in the block and material piece they belong to. With `meet_finer`, a
// quad with a side on `in`'s edge also takes the finer ring's vertex on that side
// (where it put it: on the segment), so the rings share every edge vertex.
void FarTerrain::AddQuads(const sim::Terrain& terrain, const RingLattice& r, const GridWindow& in,
                          int s, bool meet_finer) {
  const double c = terrain.cell_size_m();
  for (std::size_t b = 0; b + 1 < r.ys.size(); ++b) {
    for (std::size_t a = 0; a + 1 < r.xs.size(); ++a) {
      const int x0 = r.xs[a], x1 = r.xs[a + 1], y0 = r.ys[b], y1 = r.ys[b + 1];
      if (x0 >= in.i0 && x1 <= in.i1 && y0 >= in.j0 && y1 <= in.j1) {
        continue;  // inside: drawn by the ring within or the near window
      }
      const int ci = std::min(x0 + s / 2, terrain.cols() - 2);
      const int cj = std::min(y0 + s / 2, terrain.rows() - 2);
      Piece& p = PieceFor(static_cast<int>(a) / kBlockQuads, static_cast<int>(b) / kBlockQuads,
                          terrain.CellMaterial(ci, cj));
      const auto first = static_cast<std::uint32_t>(p.vertices.size());
      const std::array<std::size_t, 4> corner = {r.at(a, b), r.at(a + 1, b), r.at(a + 1, b + 1),
                                                 r.at(a, b + 1)};
      for (std::size_t k = 0; k < 4; ++k) {
        AddVertex(&p, terrain.x_min() + r.xs[a + (k == 1 || k == 2)] * c,
                  terrain.y_min() + r.ys[b + (k >= 2)] * c, r.z[corner[k]], r.n[corner[k]], 0.0);
      }
      // The side on the finer ring's edge, if any: 0 bottom, 1 right, 2 top, 3 left.
      const bool along_x = x0 >= in.i0 && x1 <= in.i1, along_y = y0 >= in.j0 && y1 <= in.j1;
      int side = -1;
      if (meet_finer && along_x && y0 == in.j1) side = 0;
      if (meet_finer && along_y && x1 == in.i0) side = 1;
      if (meet_finer && along_x && y1 == in.j0) side = 2;
      if (meet_finer && along_y && x0 == in.i1) side = 3;
      const int lo = side % 2 == 0 ? x0 : y0, hi = side % 2 == 0 ? x1 : y1;
      const int mid = (lo / (s / 2) + 1) * (s / 2);  // the finer ring's next lattice position
      if (side < 0 || mid >= hi) {
        p.indices.insert(p.indices.end(),
                         {first, first + 1, first + 2, first, first + 2, first + 3});
        continue;
      }
      // The finer ring's vertex, as it computed it: between the side's ends (lower first).
      static constexpr std::array<std::array<int, 2>, 4> kEnds = {{{0, 1}, {1, 2}, {3, 2}, {0, 3}}};
      const std::size_t e0 = corner[kEnds[side][0]], e1 = corner[kEnds[side][1]];
      const double f = static_cast<double>(mid - lo) / (hi - lo);
      const double x = side % 2 == 0 ? mid : (side == 1 ? x1 : x0);
      const double y = side % 2 == 1 ? mid : (side == 0 ? y0 : y1);
      AddVertex(&p, terrain.x_min() + x * c, terrain.y_min() + y * c,
                r.z[e0] + f * (r.z[e1] - r.z[e0]), ((1 - f) * r.n[e0] + f * r.n[e1]).normalized(),
                0.0);
      // The triangle holding that side split at the new vertex (4), the other as it was.
      static constexpr std::array<std::array<std::uint32_t, 9>, 4> kSplit = {{
          {0, 4, 2, 4, 1, 2, 0, 2, 3},  // bottom: in (0, 1, 2)
          {0, 1, 4, 0, 4, 2, 0, 2, 3},  // right: in (0, 1, 2)
          {0, 1, 2, 0, 2, 4, 0, 4, 3},  // top: in (0, 2, 3)
          {0, 1, 2, 0, 2, 4, 2, 3, 4},  // left: in (0, 2, 3)
      }};
      for (const std::uint32_t k : kSplit[side]) p.indices.push_back(first + k);
    }
  }
}

// Skirts hanging from the first ring's inner edge, on every side of the near window
// that is not the grid's edge: down past the lowest grid vertex between two lattice
// vertices, double-sided.
void FarTerrain::AddSkirts(const sim::Terrain& terrain, const RingLattice& r,
                           const GridWindow& in) {
  const double c = terrain.cell_size_m();
  // One side: along x (y fixed at grid row `fixed`, the ring's lattice row `row`) or
  // along y; `outside` is the step from the side to the cell beyond it.
  const auto side = [&](bool along_x, int fixed, int outside) {
    const std::vector<int>& pos = along_x ? r.xs : r.ys;
    const std::vector<int>& across = along_x ? r.ys : r.xs;
    const auto fixed_at = std::find(across.begin(), across.end(), fixed);
    if (fixed_at == across.end()) return;
    const auto f = static_cast<std::size_t>(fixed_at - across.begin());
    const int lo = along_x ? in.i0 : in.j0, hi = along_x ? in.i1 : in.j1;
    for (std::size_t k = 0; k + 1 < pos.size(); ++k) {
      if (pos[k] < lo || pos[k + 1] > hi) continue;
      const auto vertex = [&](std::size_t q) { return along_x ? r.at(q, f) : r.at(f, q); };
      const auto grid_height = [&](int q) {
        return along_x ? terrain.VertexHeight(q, fixed) : terrain.VertexHeight(fixed, q);
      };
      const double z0 = r.z[vertex(k)], z1 = r.z[vertex(k + 1)];
      double depth = 0.05;
      for (int q = pos[k]; q <= pos[k + 1]; ++q) {
        const double line = z0 + (z1 - z0) * (q - pos[k]) / (pos[k + 1] - pos[k]);
        depth = std::max(depth, line - grid_height(q) + 0.05);
      }
      const int mid = (pos[k] + pos[k + 1]) / 2;
      const int ci =
          std::clamp(along_x ? mid : fixed + std::min(outside, 0), 0, terrain.cols() - 2);
      const int cj =
          std::clamp(along_x ? fixed + std::min(outside, 0) : mid, 0, terrain.rows() - 2);
      const auto block = static_cast<int>(k) / kBlockQuads;
      const auto block_across = static_cast<int>(f) / kBlockQuads;
      Piece& p = PieceFor(along_x ? block : block_across, along_x ? block_across : block,
                          terrain.CellMaterial(ci, cj));
      const auto first = static_cast<std::uint32_t>(p.vertices.size());
      for (const std::size_t q : {k, k + 1}) {
        const double x = terrain.x_min() + (along_x ? pos[q] : fixed) * c;
        const double y = terrain.y_min() + (along_x ? fixed : pos[q]) * c;
        AddVertex(&p, x, y, r.z[vertex(q)], r.n[vertex(q)], 0.0);
        AddVertex(&p, x, y, r.z[vertex(q)] - depth, r.n[vertex(q)], depth);
      }
      // top0, bottom0, top1, bottom1; both faces.
      p.indices.insert(p.indices.end(), {first, first + 1, first + 3, first, first + 3, first + 2,
                                         first, first + 3, first + 1, first, first + 2, first + 3});
    }
  };
  if (in.j0 > 0) side(true, in.j0, -1);
  if (in.j1 < terrain.rows() - 1) side(true, in.j1, 1);
  if (in.i0 > 0) side(false, in.i0, -1);
  if (in.i1 < terrain.cols() - 1) side(false, in.i1, 1);
}

}  // namespace trackbed::render
