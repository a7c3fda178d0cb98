// The rendered terrain's levels of detail: exact near the rig, no cracks
// between chunks meshed at different levels, coarse meshes equal to the blended
// fine surface, and a ground that changes by fractions of a millimetre per frame.
#include "trackbed/render/terrain_detail.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include <gtest/gtest.h>

namespace trackbed::render {
namespace {

// The outdoor park's ground (scenes/outdoor.yaml), with a second material.
sim::TerrainOptions Park() {
  sim::TerrainOptions o;
  o.extent_m = {-13, -11, 13, 11};
  o.cell_size_m = 0.1;
  o.roughness.undulation_amplitude_m = 0.25;
  o.roughness.undulation_wavelength_m = 7.0;
  o.roughness.bump_amplitude_m = 0.03;
  o.roughness.bump_wavelength_m = 0.7;
  o.default_material = "grass";
  sim::MaterialRegion sand;
  sand.material = "dry_sand";
  sand.min_m = {-7, -6.5};
  sand.max_m = {1, 1};
  o.regions.push_back(sand);
  return o;
}

constexpr double kFullDetail = 3.0;

// Height of a chunk's mesh at grid vertex (i, j) inside it, by interpolation on
// the mesh's triangles (the split along (a, b)–(a+1, b+1)).
double MeshHeight(const TerrainDetail::Chunk& c, const TerrainDetail::Mesh& m, int i, int j) {
  const int s = 1 << m.level;
  const int na = (c.i1 - c.i0) / s;
  const int a = std::min((i - c.i0) / s, na - 1),
            b = std::min((j - c.j0) / s, (c.j1 - c.j0) / s - 1);
  const double u = static_cast<double>(i - c.i0 - a * s) / s,
               v = static_cast<double>(j - c.j0 - b * s) / s;
  const auto z = [&](int aa, int bb) {
    return static_cast<double>(m.vertices[static_cast<std::size_t>(bb * (na + 1) + aa)].z);
  };
  if (u >= v) return (1 - u) * z(a, b) + (u - v) * z(a + 1, b) + v * z(a + 1, b + 1);
  return (1 - v) * z(a, b) + (v - u) * z(a, b + 1) + u * z(a + 1, b + 1);
}

TEST(TerrainDetailTest, LevelIsContinuousMonotoneAndWholeOnPlateaus) {
  const sim::Terrain t(Park(), 1);
  const TerrainDetail d(t, kFullDetail);
  EXPECT_EQ(d.LevelAt(0.0), 0.0);
  EXPECT_EQ(d.LevelAt(2.99), 0.0);
  EXPECT_EQ(d.LevelAt(5.0), 1.0);  // plateau between 1.5 × and 2 ×
  EXPECT_EQ(d.LevelAt(10.0), 2.0);
  EXPECT_EQ(d.LevelAt(100.0), TerrainDetail::kMaxLevel);
  double last = 0.0;
  for (double r = 0.0; r < 30.0; r += 0.001) {
    const double g = d.LevelAt(r);
    EXPECT_GE(g, last);
    EXPECT_LE(g - last, 0.001 / (0.5 * kFullDetail) + 1e-12) << "at " << r << " m";
    last = g;
  }
  const TerrainDetail full(t, 0.0);
  EXPECT_EQ(full.LevelAt(25.0), 0.0);
}

TEST(TerrainDetailTest, WithinFullDetailTheDrawnGroundIsThePhysicalGround) {
  const sim::Terrain t(Park(), 1);
  const TerrainDetail d(t, kFullDetail);
  const Eigen::Vector2d center(4.5, 0.0);
  int checked = 0;
  for (const TerrainDetail::Chunk& c : d.chunks()) {
    TerrainDetail::Mesh m;
    d.BuildMesh(c, center, 1.0, &m);
    for (const TerrainVertex& v : m.vertices) {
      if (std::hypot(v.x - center.x(), v.y - center.y()) >= kFullDetail) continue;
      EXPECT_NEAR(v.z, t.Height(v.x, v.y), 1e-6);
      ++checked;
    }
  }
  EXPECT_GT(checked, 2000);
}

TEST(TerrainDetailTest, ChunksMeetWithoutCracksAndCoarseMeshesAreTheBlendedSurface) {
  const sim::Terrain t(Park(), 1);
  const TerrainDetail d(t, kFullDetail);
  const std::vector<TerrainDetail::Chunk>& chunks = d.chunks();
  int coarse = 0, shared = 0;
  for (const Eigen::Vector2d& center : {Eigen::Vector2d(4.5, 0.0), Eigen::Vector2d(-3.33, 2.71)}) {
    std::vector<TerrainDetail::Mesh> meshes(chunks.size());
    for (std::size_t k = 0; k < chunks.size(); ++k) d.BuildMesh(chunks[k], center, 1.0, &meshes[k]);
    const double cell = t.cell_size_m();
    for (std::size_t k = 0; k < chunks.size(); ++k) {
      const TerrainDetail::Chunk& c = chunks[k];
      if (meshes[k].level > 0) ++coarse;
      // Every grid vertex inside: the mesh is the blended surface, but for the
      // product of a blend weight and a level difference that both vary
      // linearly over a triangle (and the sides put on coarser neighbours' edges).
      for (int j = c.j0; j <= c.j1; ++j) {
        for (int i = c.i0; i <= c.i1; ++i) {
          const double x = t.x_min() + i * cell, y = t.y_min() + j * cell;
          const double blended =
              d.Height(i, j, d.LevelAt(std::hypot(x - center.x(), y - center.y())));
          ASSERT_NEAR(MeshHeight(c, meshes[k], i, j), blended, 1e-3)
              << "chunk at (" << c.i0 << ", " << c.j0 << ") level " << meshes[k].level;
        }
      }
      // Along the edges it shares with the chunk to its right and above: both
      // meshes give the same height at every grid vertex of the edge.
      for (std::size_t o = 0; o < chunks.size(); ++o) {
        const TerrainDetail::Chunk& n = chunks[o];
        if (n.i0 == c.i1 && n.j0 == c.j0) {
          for (int j = c.j0; j <= c.j1; ++j) {
            ASSERT_NEAR(MeshHeight(c, meshes[k], c.i1, j), MeshHeight(n, meshes[o], n.i0, j), 1e-6);
          }
          ++shared;
        }
        if (n.j0 == c.j1 && n.i0 == c.i0) {
          for (int i = c.i0; i <= c.i1; ++i) {
            ASSERT_NEAR(MeshHeight(c, meshes[k], i, c.j1), MeshHeight(n, meshes[o], i, n.j0), 1e-6);
          }
          ++shared;
        }
      }
    }
  }
  EXPECT_GT(coarse, 100);
  EXPECT_GT(shared, 300);
}

// The whole drawn surface is watertight: every edge of every chunk's triangles is an
// edge of exactly one other triangle, with the same vertices bit for bit, but on the
// terrain's border. A T-junction (a vertex in the middle of another triangle's edge)
// leaves that edge and the two halves beside it in one triangle each; a rasterizer
// may leave pixels open along it.
TEST(TerrainDetailTest, ChunksMeetEdgeToEdgeWithoutTJunctions) {
  const sim::Terrain t(Park(), 1);
  const TerrainDetail d(t, kFullDetail);
  using Key = std::array<float, 8>;
  const auto key = [](const TerrainVertex& v) {
    return Key{v.x, v.y, v.z, v.nx, v.ny, v.nz, v.s, v.t};
  };
  const auto on_border = [&](const TerrainVertex& v) {
    const float x0 = static_cast<float>(t.x_min()), y0 = static_cast<float>(t.y_min());
    const float x1 = static_cast<float>(t.x_min() + (t.cols() - 1) * t.cell_size_m());
    const float y1 = static_cast<float>(t.y_min() + (t.rows() - 1) * t.cell_size_m());
    return v.x == x0 || v.x == x1 || v.y == y0 || v.y == y1;
  };
  int finer_sides = 0;
  for (const Eigen::Vector2d& center :
       {Eigen::Vector2d(4.5, 0.0), Eigen::Vector2d(-3.33, 2.71), Eigen::Vector2d(-12.0, 10.0)}) {
    std::map<std::pair<Key, Key>, int> uses;
    std::map<std::pair<Key, Key>, bool> border;
    for (const TerrainDetail::Chunk& c : d.chunks()) {
      TerrainDetail::Mesh m;
      d.BuildMesh(c, center, 1.0, &m);
      finer_sides += static_cast<int>(m.vertices.size()) !=
                     ((c.i1 - c.i0) / (1 << m.level) + 1) * ((c.j1 - c.j0) / (1 << m.level) + 1);
      for (std::size_t k = 0; k < m.indices.size(); k += 3) {
        for (int e = 0; e < 3; ++e) {
          const TerrainVertex& p = m.vertices[m.indices[k + e]];
          const TerrainVertex& q = m.vertices[m.indices[k + (e + 1) % 3]];
          const std::pair<Key, Key> edge = std::minmax(key(p), key(q));
          ++uses[edge];
          border[edge] = on_border(p) && on_border(q) && (p.x == q.x || p.y == q.y);
        }
      }
    }
    int open = 0, over = 0;
    for (const auto& [edge, n] : uses) {
      open += n == 1 && !border[edge];
      over += n > 2;
    }
    EXPECT_EQ(open, 0) << "centre (" << center.transpose() << ")";
    EXPECT_EQ(over, 0) << "centre (" << center.transpose() << ")";
    EXPECT_GT(uses.size(), 30000u);
  }
  EXPECT_GT(finer_sides, 20);  // coarse chunks beside finer ones were meshed
}

TEST(TerrainDetailTest, TheGroundChangesBySubMillimetresPerFrameAsTheRigMoves) {
  const sim::Terrain t(Park(), 1);
  const TerrainDetail d(t, kFullDetail);
  // 0.4 m/s at 10 Hz: 4 cm per frame, along a straight line across the park.
  const double cell = t.cell_size_m();
  double worst = 0.0;
  for (double s = -8.0; s < 8.0; s += 0.04) {
    const Eigen::Vector2d a(s, 0.3 * s), b(s + 0.04, 0.3 * (s + 0.04));
    for (int j = 0; j < t.rows(); j += 3) {
      for (int i = 0; i < t.cols(); i += 3) {
        const double x = t.x_min() + i * cell, y = t.y_min() + j * cell;
        const double za = d.Height(i, j, d.LevelAt(std::hypot(x - a.x(), y - a.y())));
        const double zb = d.Height(i, j, d.LevelAt(std::hypot(x - b.x(), y - b.y())));
        worst = std::max(worst, std::abs(za - zb));
      }
    }
  }
  EXPECT_GT(worst, 1e-5);  // it does blend
  EXPECT_LT(worst, 0.5e-3);
}

TEST(TerrainDetailTest, FarTerrainIsDrawnWithAFractionOfTheTriangles) {
  const sim::Terrain t(Park(), 1);
  const TerrainDetail full(t, 0.0), lod(t, kFullDetail);
  std::size_t n_full = 0, n_lod = 0;
  TerrainDetail::Mesh m;
  const Eigen::Vector2d center(4.5, 0.0);
  for (const TerrainDetail::Chunk& c : full.chunks()) {
    m = {};
    full.BuildMesh(c, center, 1.0, &m);
    n_full += m.indices.size() / 3;
  }
  for (const TerrainDetail::Chunk& c : lod.chunks()) {
    m = {};
    lod.BuildMesh(c, center, 1.0, &m);
    n_lod += m.indices.size() / 3;
  }
  EXPECT_EQ(n_full, 2u * 260u * 220u);
  EXPECT_LT(n_lod, n_full * 2 / 5);
  std::printf("terrain triangles from (4.5, 0): %zu of %zu (%.1f %%)\n", n_lod, n_full,
              100.0 * n_lod / n_full);
}

}  // namespace
}  // namespace trackbed::render
