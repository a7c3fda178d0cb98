// Large mesh objects in chunks with far versions (docs/rendering.md, "mesh objects"):
// every triangle in exactly one chunk, the same split twice; far versions that keep
// the chunks' borders and the vertices' texture coordinates; the version a view picks;
// a bumpy sphere's silhouette drawn from far versions within object_far_error_px of its
// full one; fewer triangles submitted with distance; the same bytes on a second renderer.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mesh_chunks.h"
#include "mesh_far_versions.h"
#include "mesh_files.h"
#include "render_test_scene.h"
#include "trackbed/assets/mesh_reader.h"
#include "trackbed/render/renderer.h"
#include "trackbed/sim/world.h"

namespace trackbed {
namespace {

using render::MeshLevel;
using render::MeshSurface;
using render::test::Looking;

// A sphere of radius 2 m with bumps of 6 cm (r = 2 + 0.06 sin 6λ sin 5θ, λ the longitude,
// θ from the north pole), `slices` × `stacks` facets, texture coordinates (λ/2π, 1 − θ/π)
// with the seam's and the poles' vertices repeated: a closed surface whose outline
// crosses the chunks' interiors.
std::string BumpySphere(int slices, int stacks) {
  std::ostringstream obj;
  for (int j = 0; j <= stacks; ++j) {
    for (int i = 0; i <= slices; ++i) {
      const double lon = 2 * M_PI * i / slices, theta = M_PI * j / stacks;
      const double r = 2.0 + 0.06 * std::sin(6 * lon) * std::sin(5 * theta);
      obj << "v " << r * std::sin(theta) * std::cos(lon) << ' '
          << r * std::sin(theta) * std::sin(lon) << ' ' << r * std::cos(theta) << "\nvt "
          << static_cast<double>(i) / slices << ' ' << 1.0 - static_cast<double>(j) / stacks
          << '\n';
    }
  }
  const auto at = [&](int i, int j) { return j * (slices + 1) + i + 1; };
  const auto corner = [](int v) { return std::to_string(v) + "/" + std::to_string(v); };
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      const int a = at(i, j), b = at(i, j + 1), c = at(i + 1, j + 1), d = at(i + 1, j);
      // Counter-clockwise from outside; no triangle with two corners on a pole.
      if (j > 0) obj << "f " << corner(a) << ' ' << corner(b) << ' ' << corner(d) << '\n';
      if (j < stacks - 1) obj << "f " << corner(b) << ' ' << corner(c) << ' ' << corner(d) << '\n';
    }
  }
  return test_mesh::Write("bumpy_sphere.obj", obj.str());
}

sim::MeshObject MeshAt(const std::string& file, double x, double y, double z) {
  sim::MeshObject m;
  m.entry.shape = sim::StaticObject::Shape::kMesh;
  m.entry.kind = "mesh";
  m.entry.mesh.file = file;
  m.entry.center_m = Eigen::Vector2d(x, y);
  m.entry.base_z_m = z;
  m.visual = std::make_shared<const sim::TriangleMesh>(assets::ReadMesh(file).mesh);
  return m;
}

// A triangle as its three vertices' bytes, to compare triangles across vertex buffers.
using TriangleBytes = std::array<std::array<unsigned char, sizeof(render::TerrainVertex)>, 3>;
TriangleBytes Bytes(const MeshSurface& s, std::size_t t) {
  TriangleBytes b{};
  for (int k = 0; k < 3; ++k)
    std::memcpy(b[k].data(), &s.vertices[s.indices[3 * t + k]], sizeof(render::TerrainVertex));
  return b;
}

// The sphere's one part (25 280 triangles) placed at (0, 0, 3).
MeshSurface SpherePart() {
  const std::vector<MeshSurface> parts =
      render::MeshSurfaces(MeshAt(BumpySphere(160, 80), 0, 0, 3));
  EXPECT_EQ(parts.size(), 1u);
  return parts.front();
}

TEST(MeshChunksTest, EveryTriangleInExactlyOneChunkTheSameSplitTwice) {
  const MeshSurface part = SpherePart();
  const std::size_t n = part.indices.size() / 3;
  ASSERT_EQ(n, 25280u);
  const std::vector<MeshSurface> chunks = render::SplitMeshSurface(part, 1000);
  std::multiset<TriangleBytes> all, chunked;
  for (std::size_t t = 0; t < n; ++t) all.insert(Bytes(part, t));
  for (const MeshSurface& c : chunks) {
    EXPECT_LE(c.indices.size() / 3, 1000u);
    EXPECT_GE(c.indices.size() / 3, 500u);
    EXPECT_EQ(c.texture_key, part.texture_key);
    for (std::size_t t = 0; t < c.indices.size() / 3; ++t) chunked.insert(Bytes(c, t));
    for (const render::TerrainVertex& v : c.vertices)
      EXPECT_TRUE(c.box.contains(Eigen::Vector3d(v.x, v.y, v.z)));
  }
  EXPECT_GE(chunks.size(), 26u);
  EXPECT_TRUE(all == chunked);  // the same triangles, each once, with the same vertices
  const std::vector<MeshSurface> again = render::SplitMeshSurface(part, 1000);
  ASSERT_EQ(again.size(), chunks.size());
  for (std::size_t c = 0; c < chunks.size(); ++c) EXPECT_EQ(again[c].indices, chunks[c].indices);
  // A part within the limit stays whole.
  EXPECT_EQ(render::SplitMeshSurface(part, n).size(), 1u);
}

TEST(MeshChunksTest, FarVersionsKeepTheChunksBordersAndDepartFurther) {
  std::vector<MeshSurface> chunks = render::SplitMeshSurface(SpherePart(), 4000);
  for (MeshSurface& c : chunks) {
    const std::vector<MeshLevel> levels = render::AddMeshFarVersions(&c);
    ASSERT_GE(levels.size(), 3u);
    // The border: edges (by position) of one triangle of the full version.
    const auto key = [&](std::uint32_t v) {
      const render::TerrainVertex& p = c.vertices[v];
      return std::array<float, 3>{p.x, p.y, p.z};
    };
    const auto edges = [&](const MeshLevel& l) {
      std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> count;
      for (std::uint32_t i = l.first_index; i < l.first_index + l.index_count; i += 3)
        for (int k = 0; k < 3; ++k) {
          auto a = key(c.indices[i + k]), b = key(c.indices[i + (k + 1) % 3]);
          ++count[{std::min(a, b), std::max(a, b)}];
        }
      std::set<std::pair<std::array<float, 3>, std::array<float, 3>>> border;
      for (const auto& [e, k] : count)
        if (k == 1) border.insert(e);
      return border;
    };
    const auto border = edges(levels[0]);
    EXPECT_GT(border.size(), 0u);
    for (std::size_t l = 1; l < levels.size(); ++l) {
      EXPECT_LT(levels[l].index_count, levels[l - 1].index_count);
      EXPECT_GE(levels[l].departure_m, levels[l - 1].departure_m);
      EXPECT_EQ(edges(levels[l]), border) << "version " << l;
    }
    EXPECT_GT(levels.back().departure_m, 0.0);
  }
}

TEST(MeshChunksTest, AViewDrawsTheCoarsestVersionWithinTheBound) {
  const std::vector<MeshLevel> levels = {{0, 300, 0.0}, {300, 60, 0.01}, {360, 15, 0.04}};
  // Nearest side 10 m away in plan: at f = 300 px, 0.01 m is 0.3 px and 0.04 m 1.2 px.
  const Eigen::AlignedBox3d box(Eigen::Vector3d(10, -1, 0), Eigen::Vector3d(12, 1, 50));
  const Eigen::Vector2d center(0, 0);
  EXPECT_EQ(render::MeshLevelAt(levels, box, center, 300, 1.0).index_count, 60u);
  EXPECT_EQ(render::MeshLevelAt(levels, box, center, 300, 1.5).index_count, 15u);
  EXPECT_EQ(render::MeshLevelAt(levels, box, center, 300, 0.2).index_count, 300u);
  EXPECT_EQ(render::MeshLevelAt(levels, box, center, 300, 0.0).index_count, 300u);
  EXPECT_EQ(render::MeshLevelAt(levels, box, {11, 0}, 300, 1.5).index_count, 300u);  // inside
}

geometry::PinholeCamera Camera() {
  geometry::PinholeCamera K;
  K.width_px = 320;
  K.height_px = 240;
  K.fx = K.fy = 300.0;
  K.cx = 159.5;
  K.cy = 119.5;
  return K;
}

struct View {
  render::DepthImage depth;
  GrayImage gray;
  std::size_t triangles = 0;
};

// The sphere `distance_m` ahead of a level camera at 3 m, both at the same height.
View SphereView(double distance_m, double error_px) {
  sim::TerrainOptions t;
  t.extent_m = {-4, -4, 4, 4};
  t.cell_size_m = 0.5;
  std::vector<sim::MeshObject> meshes = {MeshAt(BumpySphere(160, 80), distance_m, 0, 3)};
  const sim::World world(sim::WorldOptions{}, sim::Terrain(t, 1), {}, std::move(meshes));
  render::SceneAppearance a = render::test::AmbientOnly();
  a.object_far_error_px = error_px;
  const geometry::PinholeCamera K = Camera();
  render::Renderer r(world, a, {}, 7, K.width_px, K.height_px, 0.1, 60.0);
  View v;
  const Eigen::Isometry3d T = Looking({0, 0, 3}, {1, 0, 0});
  r.Render(K, T, 0.0, &v.gray, &v.depth);
  v.triangles = r.mesh_triangles_submitted();
  return v;
}

// The sphere's pixels: nearer than its far side.
std::vector<bool> Covered(const View& v, double distance_m) {
  std::vector<bool> m(v.depth.depth_m.size());
  for (std::size_t k = 0; k < m.size(); ++k) m[k] = v.depth.depth_m[k] < distance_m + 2.5;
  return m;
}

TEST(MeshChunksTest, FarVersionsMoveTheOutlineByLessThanTheBound) {
  const double error_px = 1.0;
  for (const double d : {8.0, 16.0}) {
    const View full = SphereView(d, 0.0), far = SphereView(d, error_px);
    EXPECT_EQ(full.triangles, 25280u);
    EXPECT_LT(far.triangles, full.triangles / 2) << "at " << d << " m";
    const std::vector<bool> a = Covered(full, d), b = Covered(far, d);
    // Each pixel the far versions cover differently lies within the bound, and the pixel
    // a centre's sampling adds, of a pixel the full version covers as the far one does.
    const int reach = static_cast<int>(std::ceil(error_px)) + 1;
    int changed = 0, worst = 0;
    double grey = 0.0;
    int both = 0;
    for (int r = 0; r < 240; ++r)
      for (int c = 0; c < 320; ++c) {
        const std::size_t k = static_cast<std::size_t>(r) * 320 + c;
        if (a[k] && b[k]) {
          grey += std::abs(full.gray.pixels[k] - far.gray.pixels[k]);
          ++both;
        }
        if (a[k] == b[k]) continue;
        ++changed;
        // The nearest pixel (in rings, up to 10 px) the full version covers as the far one does.
        int ring = 1;
        for (bool found = false; !found && ring <= 10; ring += !found) {
          for (int dr = -ring; dr <= ring && !found; ++dr)
            for (int dc = -ring; dc <= ring && !found; ++dc) {
              const int rr = r + dr, cc = c + dc;
              found = rr >= 0 && rr < 240 && cc >= 0 && cc < 320 &&
                      a[static_cast<std::size_t>(rr) * 320 + cc] == b[k];
            }
        }
        worst = std::max(worst, ring);
      }
    EXPECT_LE(worst, reach) << "at " << d << " m, " << changed << " pixels changed";
    std::printf(
        "at %.0f m: %zu of %zu triangles submitted; %d pixels covered differently, each within "
        "%d px of one the full version covers alike; mean grey difference where both cover %.2f\n",
        d, far.triangles, full.triangles, changed, worst, grey / std::max(both, 1));
  }
}

TEST(MeshChunksTest, FewerTrianglesSubmittedFurtherAwayTheSameBytesTwice) {
  std::size_t previous = 25281;
  for (const double d : {4.0, 8.0, 16.0, 32.0}) {
    const View v = SphereView(d, 1.0);
    EXPECT_LE(v.triangles, previous) << "at " << d << " m";
    if (d == 32.0) {
      EXPECT_LT(v.triangles, 25280u / 8);
    }
    previous = v.triangles;
  }
  const View a = SphereView(16.0, 1.0), b = SphereView(16.0, 1.0);
  EXPECT_EQ(a.gray.pixels, b.gray.pixels);
  EXPECT_EQ(a.depth.depth_m, b.depth.depth_m);
}

}  // namespace
}  // namespace trackbed
