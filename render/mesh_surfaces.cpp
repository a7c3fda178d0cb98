// Mesh objects as the renderer draws them (see mesh_surfaces.h).
#include "mesh_surfaces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <unordered_map>

namespace trackbed::render {
namespace {

// Rec. 709's luma weights of linear red, green and blue.
constexpr double kLuma[3] = {0.2126, 0.7152, 0.0722};

// A key of exact bits (a position, or a vertex index with its normal).
template <int N>
struct Bits {
  std::array<std::uint32_t, N> b;
  bool operator==(const Bits& o) const { return b == o.b; }
};
template <int N>
struct BitsHash {
  std::size_t operator()(const Bits<N>& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t x : k.b) h = (h ^ x) * 1099511628211ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};
template <int N>
Bits<N> BitsOf(const float (&f)[N]) {
  Bits<N> k{};
  std::memcpy(k.b.data(), f, sizeof f);
  return k;
}

// Each corner's normal (3 per triangle), in the world frame (see mesh_surfaces.h).
std::vector<Eigen::Vector3f> CornerNormals(const std::vector<Eigen::Vector3d>& world,
                                           const sim::TriangleMesh& mesh) {
  const std::size_t n = mesh.triangles.size();
  // Vertices grouped by position: the triangles about each position.
  std::vector<std::uint32_t> group(world.size());
  std::unordered_map<Bits<3>, std::uint32_t, BitsHash<3>> groups;
  for (std::size_t v = 0; v < world.size(); ++v) {
    const Eigen::Vector3f& p = mesh.vertices[v];
    const float f[3] = {p.x(), p.y(), p.z()};
    group[v] = groups.emplace(BitsOf(f), static_cast<std::uint32_t>(groups.size())).first->second;
  }
  std::vector<std::uint32_t> start(groups.size() + 1, 0), about(3 * n);
  for (const auto& t : mesh.triangles)
    for (std::uint32_t v : t) ++start[group[v] + 1];
  for (std::size_t g = 0; g < groups.size(); ++g) start[g + 1] += start[g];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  std::vector<Eigen::Vector3d> face(n);  // area-weighted: twice the area's length
  for (std::size_t k = 0; k < n; ++k) {
    const auto& t = mesh.triangles[k];
    face[k] = (world[t[1]] - world[t[0]]).cross(world[t[2]] - world[t[0]]);
    for (std::uint32_t v : t) about[fill[group[v]]++] = static_cast<std::uint32_t>(k);
  }
  const double crease = std::cos(kCreaseDeg * M_PI / 180.0);
  std::vector<Eigen::Vector3f> corners(3 * n);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d own = face[k].normalized();
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t g = group[mesh.triangles[k][c]];
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (std::uint32_t i = start[g]; i < start[g + 1]; ++i) {
        const Eigen::Vector3d& f = face[about[i]];
        if (f.dot(own) >= crease * f.norm()) sum += f;
      }
      const double length = sum.norm();
      corners[3 * k + c] =
          (length > 0.0 ? Eigen::Vector3d(sum / length) : Eigen::Vector3d::UnitZ()).cast<float>();
    }
  }
  return corners;
}

// The key of a part's texture: its image (by identity) and base colour.
std::string TextureKey(const sim::MeshPart& part) {
  char text[128];
  std::snprintf(text, sizeof text, "mesh image %p colour %.9g %.9g %.9g",
                static_cast<const void*>(part.base_color_image.get()), part.base_color.x(),
                part.base_color.y(), part.base_color.z());
  return text;
}

// Resamples `n` samples of a row or column (stride `step`) to `m`: each output the mean
// of the input over its span (when shrinking) or linearly interpolated (when growing),
// wrapping around as the texture repeats.
void Resample(const double* in, int n, int in_step, double* out, int m, int out_step) {
  const double ratio = static_cast<double>(n) / m;
  for (int i = 0; i < m; ++i) {
    double value = 0.0;
    if (ratio <= 1.0) {
      const double x = (i + 0.5) * ratio - 0.5;
      const double x0 = std::floor(x), w = x - x0;
      const int a = (static_cast<int>(x0) % n + n) % n, b = (a + 1) % n;
      value = (1.0 - w) * in[a * in_step] + w * in[b * in_step];
    } else {
      const double lo = i * ratio, hi = (i + 1) * ratio;
      for (int k = static_cast<int>(std::floor(lo)); k < hi; ++k) {
        const double overlap = std::min(hi, k + 1.0) - std::max(lo, static_cast<double>(k));
        value += overlap * in[(k % n) * in_step];
      }
      value /= ratio;
    }
    out[i * out_step] = value;
  }
}

}  // namespace

double SrgbToLinear(std::uint8_t encoded) {
  const double c = encoded / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

Texture MeshPartTexture(const sim::MeshPart& part) {
  Texture t;
  const Eigen::Vector3d colour = part.base_color.head<3>().cast<double>().cwiseMax(0.0);
  const sim::MeshImage* image = part.base_color_image.get();
  if (image == nullptr) {
    t.size_px = 16;
    const double y = kLuma[0] * colour.x() + kLuma[1] * colour.y() + kLuma[2] * colour.z();
    t.texels.assign(16 * 16, static_cast<std::uint8_t>(std::lround(std::clamp(y, 0.0, 1.0) * 255)));
    return t;
  }
  std::array<double, 256> linear;
  for (int k = 0; k < 256; ++k) linear[k] = SrgbToLinear(static_cast<std::uint8_t>(k));
  const int w = image->width, h = image->height;
  // Grey, rows bottom first (texture coordinate v upwards).
  std::vector<double> grey(static_cast<std::size_t>(w) * h);
  for (int r = 0; r < h; ++r) {
    const std::uint8_t* src = &image->rgb[static_cast<std::size_t>(h - 1 - r) * w * 3];
    for (int c = 0; c < w; ++c) {
      grey[static_cast<std::size_t>(r) * w + c] = kLuma[0] * colour.x() * linear[src[3 * c]] +
                                                  kLuma[1] * colour.y() * linear[src[3 * c + 1]] +
                                                  kLuma[2] * colour.z() * linear[src[3 * c + 2]];
    }
  }
  int size = 16;
  while (size < std::max(w, h) && size < 2048) size *= 2;
  std::vector<double> rows(static_cast<std::size_t>(size) * h);  // w → size, per row
  for (int r = 0; r < h; ++r) {
    Resample(&grey[static_cast<std::size_t>(r) * w], w, 1,
             &rows[static_cast<std::size_t>(r) * size], size, 1);
  }
  std::vector<double> square(static_cast<std::size_t>(size) * size);
  for (int c = 0; c < size; ++c) Resample(&rows[c], h, size, &square[c], size, size);
  t.size_px = size;
  t.texels.resize(square.size());
  for (std::size_t k = 0; k < square.size(); ++k) {
    t.texels[k] = static_cast<std::uint8_t>(std::lround(std::clamp(square[k], 0.0, 1.0) * 255));
  }
  return t;
}

std::vector<MeshSurface> MeshSurfaces(const sim::MeshObject& m) {
  const sim::TriangleMesh& mesh = *m.visual;
  const Eigen::Isometry3d pose = m.Pose();
  std::vector<Eigen::Vector3d> world;
  world.reserve(mesh.vertices.size());
  for (const Eigen::Vector3f& v : mesh.vertices) {
    world.push_back(pose * Eigen::Vector3d(v.cast<double>().cwiseProduct(m.entry.mesh.scale)));
  }
  const std::vector<Eigen::Vector3f> normals = CornerNormals(world, mesh);
  std::vector<MeshSurface> surfaces;
  for (const sim::MeshPart& part : mesh.parts) {
    if (part.triangles == 0) continue;
    MeshSurface s;
    s.part = &part;
    s.texture_key = TextureKey(part);
    // A vertex per (file vertex, normal): smooth corners share one.
    std::unordered_map<Bits<4>, std::uint32_t, BitsHash<4>> index;
    for (std::uint32_t k = part.first_triangle; k < part.first_triangle + part.triangles; ++k) {
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = mesh.triangles[k][c];
        const Eigen::Vector3f& n = normals[3 * k + c];
        float key[4] = {0.0f, n.x(), n.y(), n.z()};
        std::memcpy(&key[0], &v, sizeof v);
        const auto [it, added] =
            index.emplace(BitsOf(key), static_cast<std::uint32_t>(s.vertices.size()));
        if (added) {
          const Eigen::Vector3f p = world[v].cast<float>();
          const Eigen::Vector2f uv = mesh.uvs.empty() ? Eigen::Vector2f::Zero() : mesh.uvs[v];
          s.vertices.push_back({p.x(), p.y(), p.z(), n.x(), n.y(), n.z(), uv.x(), uv.y()});
          s.box.extend(world[v]);
        }
        s.indices.push_back(it->second);
      }
    }
    surfaces.push_back(std::move(s));
  }
  return surfaces;
}

}  // namespace trackbed::render
