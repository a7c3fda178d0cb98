// A mesh object's large parts split into chunks (see mesh_chunks.h).
#include "mesh_chunks.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace trackbed::render {
namespace {

// The triangles `ids` of `s` as one chunk: the vertices they use, in the order first used.
MeshSurface Chunk(const MeshSurface& s, std::vector<std::uint32_t> ids,
                  std::vector<std::uint32_t>* remap) {
  std::sort(ids.begin(), ids.end());
  MeshSurface c;
  c.texture_key = s.texture_key;
  c.part = s.part;
  c.indices.reserve(3 * ids.size());
  for (std::uint32_t t : ids) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = s.indices[3 * t + static_cast<std::size_t>(k)];
      std::uint32_t& to = (*remap)[v];
      if (to == std::numeric_limits<std::uint32_t>::max()) {
        to = static_cast<std::uint32_t>(c.vertices.size());
        c.vertices.push_back(s.vertices[v]);
        const TerrainVertex& p = s.vertices[v];
        c.box.extend(Eigen::Vector3d(p.x, p.y, p.z));
      }
      c.indices.push_back(to);
    }
  }
  for (std::uint32_t t : ids)  // the map cleared for the next chunk
    for (int k = 0; k < 3; ++k)
      (*remap)[s.indices[3 * t + static_cast<std::size_t>(k)]] =
          std::numeric_limits<std::uint32_t>::max();
  return c;
}

struct Splitter {
  const MeshSurface& s;
  std::size_t max_triangles;
  std::vector<Eigen::Vector3d> centroids;
  std::vector<std::uint32_t> remap;
  std::vector<MeshSurface> chunks;

  // Splits the triangles [begin, end) of `ids` at their median along their bounds'
  // longest side until each piece is small enough.
  void Split(std::vector<std::uint32_t>& ids, std::size_t begin, std::size_t end) {
    if (end - begin <= max_triangles) {
      chunks.push_back(Chunk(s,
                             {ids.begin() + static_cast<std::ptrdiff_t>(begin),
                              ids.begin() + static_cast<std::ptrdiff_t>(end)},
                             &remap));
      return;
    }
    Eigen::AlignedBox3d bounds;
    for (std::size_t i = begin; i < end; ++i) bounds.extend(centroids[ids[i]]);
    int axis = 0;
    bounds.sizes().maxCoeff(&axis);  // the first of equal sides
    const std::size_t mid = begin + (end - begin) / 2;
    const auto first = ids.begin();
    std::nth_element(
        first + static_cast<std::ptrdiff_t>(begin), first + static_cast<std::ptrdiff_t>(mid),
        first + static_cast<std::ptrdiff_t>(end), [&](std::uint32_t a, std::uint32_t b) {
          const double ca = centroids[a][axis], cb = centroids[b][axis];
          return ca < cb || (ca == cb && a < b);
        });
    Split(ids, begin, mid);
    Split(ids, mid, end);
  }
};

}  // namespace

std::vector<MeshSurface> SplitMeshSurface(const MeshSurface& s, std::size_t max_triangles) {
  if (max_triangles == 0) throw std::invalid_argument("SplitMeshSurface: max_triangles is 0");
  const std::size_t n = s.indices.size() / 3;
  if (n <= max_triangles) return {s};
  Splitter splitter{s, max_triangles, {}, {}, {}};
  splitter.centroids.resize(n);
  for (std::size_t t = 0; t < n; ++t) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const TerrainVertex& p = s.vertices[s.indices[3 * t + static_cast<std::size_t>(k)]];
      sum += Eigen::Vector3d(p.x, p.y, p.z);
    }
    splitter.centroids[t] = sum / 3.0;
  }
  splitter.remap.assign(s.vertices.size(), std::numeric_limits<std::uint32_t>::max());
  std::vector<std::uint32_t> ids(n);
  for (std::size_t t = 0; t < n; ++t) ids[t] = static_cast<std::uint32_t>(t);
  splitter.Split(ids, 0, n);
  return std::move(splitter.chunks);
}

std::vector<MeshChunk> MeshChunks(const sim::MeshObject& m, bool far_versions) {
  std::vector<MeshChunk> chunks;
  for (const MeshSurface& s : MeshSurfaces(m)) {
    for (MeshSurface& piece : SplitMeshSurface(s, kMeshChunkTriangles)) {
      MeshChunk c{std::move(piece), {}};
      c.levels = far_versions ? AddMeshFarVersions(&c) : MeshFullVersion(c);
      chunks.push_back(std::move(c));
    }
  }
  return chunks;
}

}  // namespace trackbed::render
