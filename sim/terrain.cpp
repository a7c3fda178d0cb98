// Heightfield terrain: seeded value-noise roughness, material regions, and
// surface queries that match Bullet's triangulation (see terrain.h).
#include "trackbed/sim/terrain.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "trackbed/common/option_error.h"
#include "trackbed/common/split_mix.h"

namespace trackbed::sim {

void TerrainRoughness::Validate() const {
  option_check::NonNegative("undulation_amplitude_m", undulation_amplitude_m);
  option_check::Positive("undulation_wavelength_m", undulation_wavelength_m);
  option_check::NonNegative("bump_amplitude_m", bump_amplitude_m);
  option_check::Positive("bump_wavelength_m", bump_wavelength_m);
  option_check::InRange("slope_x", slope_x, -1.0, 1.0);
  option_check::InRange("slope_y", slope_y, -1.0, 1.0);
}

bool MaterialRegion::Contains(double x, double y) const {
  if (shape == Shape::kCircle) {
    return (Eigen::Vector2d(x, y) - center_m).squaredNorm() <= radius_m * radius_m;
  }
  return x >= min_m.x() && x <= max_m.x() && y >= min_m.y() && y <= max_m.y();
}

void MaterialRegion::Validate() const {
  if (material.empty()) throw OptionError("material", "must name a material");
  if (shape == Shape::kCircle) {
    option_check::Positive("radius_m", radius_m);
  } else if (!(max_m.x() > min_m.x() && max_m.y() > min_m.y())) {
    throw OptionError("max", "must exceed min in both x and y");
  }
}

void DemOptions::Validate() const {
  if (!origin_m.allFinite()) throw OptionError("origin", "must be two finite numbers [m]");
}

void HeightmapOptions::Validate() const {
  if (file.empty()) throw OptionError("file", "must name the heightmap's image");
  for (int k = 0; k < 3; ++k) {
    if (!(std::isfinite(size_m[k]) && size_m[k] > 0.0)) {
      throw OptionError("size_m", "must be three numbers > 0 [m]");
    }
  }
  if (!pos_m.allFinite()) throw OptionError("pos_m", "must be three finite numbers [m]");
}

double TerrainOptions::cells() const {
  return (extent_m[2] - extent_m[0]) * (extent_m[3] - extent_m[1]) / (cell_size_m * cell_size_m);
}

Eigen::Vector4d TerrainOptions::grid_extent_m() const {
  const double x0 = extent_m[0], y0 = extent_m[1];
  return {x0, y0, x0 + cell_size_m * std::ceil((extent_m[2] - x0) / cell_size_m),
          y0 + cell_size_m * std::ceil((extent_m[3] - y0) / cell_size_m)};
}

void TerrainOptions::Validate() const {
  if (!(extent_m[2] > extent_m[0] && extent_m[3] > extent_m[1])) {
    throw OptionError("extent_m", "must be [x_min, y_min, x_max, y_max] with max > min");
  }
  // Within 10 km of the origin a float vertex position (the renderer's) resolves
  // 2^-10 m, under a millimetre; tiles keep the memory bounded at any area.
  for (int k = 0; k < 4; ++k) {
    if (!(std::abs(extent_m[k]) <= kMaxSideM)) {
      throw OptionError("extent_m", "must lie within ±10000 m of the origin (got " +
                                        option_check::Describe(extent_m[k]) + ")");
    }
  }
  if (extent_m[2] - extent_m[0] > kMaxSideM || extent_m[3] - extent_m[1] > kMaxSideM) {
    throw OptionError("extent_m", "must be at most 10000 m a side");
  }
  option_check::InRange("cell_size_m", cell_size_m, 0.01, 2.0);
  option_check::Nested("roughness", roughness);
  for (std::size_t k = 0; k < materials.size(); ++k) {
    option_check::Nested("materials[" + std::to_string(k) + "]", materials[k]);
  }
  option_check::Nested("soil_variation", soil_variation);
  option_check::Nested("dem", dem);
  if (heightmap) {
    option_check::Nested("heightmap", *heightmap);
    if (dem.enabled()) {
      throw OptionError("heightmap",
                        "a heightmap and dem exclude each other (both give the heights)");
    }
  }
  for (std::size_t k = 0; k < regions.size(); ++k) {
    option_check::Nested("regions[" + std::to_string(k) + "]", regions[k]);
  }
}

int TerrainOptions::RegionAt(double x, double y) const {
  for (int k = static_cast<int>(regions.size()) - 1; k >= 0; --k) {
    if (regions[static_cast<std::size_t>(k)].Contains(x, y)) return k;
  }
  return -1;
}

const std::string& TerrainOptions::MaterialNameAt(double x, double y) const {
  const int k = RegionAt(x, y);
  return k < 0 ? default_material : regions[static_cast<std::size_t>(k)].material;
}

namespace {

const TerrainOptions& Validated(const TerrainOptions& options) {
  options.Validate();
  return options;
}

// The streams of the terrain seed: the heights' four octaves, the soil variation.
constexpr std::uint64_t kHeightStream = 0x4e16, kSoilVariationStream = 0x5011;

// The stream of the height octave `octave`.
std::uint64_t HeightStream(std::uint64_t seed, std::uint64_t octave) {
  return split_mix::Stream(split_mix::Stream(seed, kHeightStream), octave);
}

}  // namespace

Terrain::Terrain(const TerrainOptions& options, std::uint64_t seed,
                 std::shared_ptr<const ElevationGrid> base)
    : options_(Validated(options)),
      // Two octaves for each of undulation and bumps, each a lattice noise of
      // the seed alone, so a point's height does not depend on the extent nor
      // on the tile it is computed in.
      hills_(HeightStream(seed, 0), options.roughness.undulation_wavelength_m),
      hills2_(HeightStream(seed, 1), options.roughness.undulation_wavelength_m / 2.0),
      bumps_(HeightStream(seed, 2), options.roughness.bump_wavelength_m),
      bumps2_(HeightStream(seed, 3), options.roughness.bump_wavelength_m / 2.0),
      base_(std::move(base)),
      soil_variation_(options.soil_variation, split_mix::Stream(seed, kSoilVariationStream)) {
  cell_ = options.cell_size_m;
  x0_ = options.extent_m[0];
  y0_ = options.extent_m[1];
  cols_ = static_cast<int>(std::ceil((options.extent_m[2] - x0_) / cell_)) + 1;
  rows_ = static_cast<int>(std::ceil((options.extent_m[3] - y0_) / cell_)) + 1;
  const TerrainRoughness& r = options.roughness;
  const double plane_lo = std::min(r.slope_x * x0_, r.slope_x * x_max()) +
                          std::min(r.slope_y * y0_, r.slope_y * y_max());
  const double plane_hi = std::max(r.slope_x * x0_, r.slope_x * x_max()) +
                          std::max(r.slope_y * y0_, r.slope_y * y_max());
  const double reach = r.undulation_amplitude_m + r.bump_amplitude_m;
  min_bound_ = plane_lo - reach + (base_ ? base_->min_height_m() : 0.0);
  max_bound_ = plane_hi + reach + (base_ ? base_->max_height_m() : 0.0);
  if (base_ && !base_->Covers(x0_, y0_, x_max(), y_max())) {
    throw OptionError("dem", "the elevation model does not cover the terrain's grid");
  }
  ResolveMaterials(options);
}

// Materials: built-ins, then the scenario's own (which may shadow a built-in);
// the default's and each region's index among them.
void Terrain::ResolveMaterials(const TerrainOptions& options) {
  materials_ = BuiltinMaterials();
  for (const TerrainMaterial& m : options.materials) {
    auto it = std::find_if(materials_.begin(), materials_.end(),
                           [&](const TerrainMaterial& b) { return b.name == m.name; });
    if (it != materials_.end()) {
      *it = m;
    } else {
      materials_.push_back(m);
    }
  }
  if (materials_.size() > 255) throw OptionError("materials", "at most 255 materials");
  for (const TerrainMaterial& m : materials_) soils_.push_back(SoilOf(m));
  auto index_of = [&](const std::string& name, const std::string& field) {
    for (std::size_t k = 0; k < materials_.size(); ++k) {
      if (materials_[k].name == name) return static_cast<std::uint8_t>(k);
    }
    std::string known;
    for (const TerrainMaterial& m : materials_) known += (known.empty() ? "" : ", ") + m.name;
    throw OptionError(field, "unknown material '" + name + "' (known: " + known + ")");
  };
  default_material_ = index_of(options.default_material, "default_material");
  for (std::size_t k = 0; k < options.regions.size(); ++k) {
    region_material_.push_back(
        index_of(options.regions[k].material, "regions[" + std::to_string(k) + "].material"));
  }
}

double Terrain::VertexHeight(int i, int j) const {
  const double x = x0_ + i * cell_, y = y0_ + j * cell_;
  const TerrainRoughness& r = options_.roughness;
  double z = r.slope_x * x + r.slope_y * y;
  if (base_) z += base_->Height(x, y);
  if (r.undulation_amplitude_m > 0.0) {
    z += r.undulation_amplitude_m * (0.75 * hills_(x, y) + 0.25 * hills2_(x, y));
  }
  if (r.bump_amplitude_m > 0.0) {
    z += r.bump_amplitude_m * (0.75 * bumps_(x, y) + 0.25 * bumps2_(x, y));
  }
  return z;
}

std::uint8_t Terrain::CellMaterial(int i, int j) const {
  const int k = options_.RegionAt(x0_ + (i + 0.5) * cell_, y0_ + (j + 0.5) * cell_);
  return k < 0 ? default_material_ : region_material_[static_cast<std::size_t>(k)];
}

TerrainTile Terrain::GenerateTile(int ti, int tj) const {
  TerrainTile t;
  t.ti = ti;
  t.tj = tj;
  t.i0 = ti * kTileCells;
  t.j0 = tj * kTileCells;
  t.cols = std::min(kTileCells, cols_ - 1 - t.i0) + 1;
  t.rows = std::min(kTileCells, rows_ - 1 - t.j0) + 1;
  t.heights.resize(static_cast<std::size_t>(t.cols) * t.rows);
  t.min_height_m = 1e300;
  t.max_height_m = -1e300;
  for (int b = 0; b < t.rows; ++b) {
    for (int a = 0; a < t.cols; ++a) {
      const double z = VertexHeight(t.i0 + a, t.j0 + b);
      t.heights[static_cast<std::size_t>(b) * t.cols + a] = z;
      t.min_height_m = std::min(t.min_height_m, z);
      t.max_height_m = std::max(t.max_height_m, z);
    }
  }
  t.cell_material.resize(static_cast<std::size_t>(t.cols - 1) * (t.rows - 1));
  for (int b = 0; b + 1 < t.rows; ++b) {
    for (int a = 0; a + 1 < t.cols; ++a) {
      t.cell_material[static_cast<std::size_t>(b) * (t.cols - 1) + a] =
          CellMaterial(t.i0 + a, t.j0 + b);
    }
  }
  return t;
}

std::shared_ptr<const TerrainTile> Terrain::Tile(int ti, int tj) const {
  if (ti < 0 || tj < 0 || ti >= tiles_x() || tj >= tiles_y()) {
    throw std::out_of_range("Terrain::Tile: no tile (" + std::to_string(ti) + ", " +
                            std::to_string(tj) + ")");
  }
  return tiles_.Get(ti, tj, [this](int a, int b) { return GenerateTile(a, b); });
}

const TerrainTile& Terrain::TileOfCell(int i, int j) const {
  const int ti = i / kTileCells, tj = j / kTileCells;
  if (!last_tile_ || last_tile_->ti != ti || last_tile_->tj != tj) last_tile_ = Tile(ti, tj);
  return *last_tile_;
}

Terrain::Facet Terrain::CellAt(double x, double y) const {
  const double gx = std::clamp((x - x0_) / cell_, 0.0, cols_ - 1.0);
  const double gy = std::clamp((y - y0_) / cell_, 0.0, rows_ - 1.0);
  Facet f;
  f.i = std::min(static_cast<int>(gx), cols_ - 2);
  f.j = std::min(static_cast<int>(gy), rows_ - 2);
  f.u = gx - f.i;
  f.v = gy - f.j;
  f.tile = nullptr;
  return f;
}

void Terrain::SetSlopes(double h00, double h10, double h01, double h11, Facet* f) {
  f->h00 = h00;
  if (f->u >= f->v) {  // triangle (i,j), (i+1,j), (i+1,j+1)
    f->dzdu = h10 - h00;
    f->dzdv = h11 - h10;
  } else {  // triangle (i,j), (i,j+1), (i+1,j+1)
    f->dzdu = h11 - h01;
    f->dzdv = h01 - h00;
  }
}

Terrain::Facet Terrain::FacetAt(double x, double y) const {
  Facet f = CellAt(x, y);
  f.tile = &TileOfCell(f.i, f.j);
  const TerrainTile& t = *f.tile;
  const std::size_t base = static_cast<std::size_t>(f.j - t.j0) * t.cols + (f.i - t.i0);
  SetSlopes(t.heights[base], t.heights[base + 1], t.heights[base + t.cols],
            t.heights[base + t.cols + 1], &f);
  return f;
}

double Terrain::HeightFromSeed(double x, double y) const {
  Facet f = CellAt(x, y);
  SetSlopes(VertexHeight(f.i, f.j), VertexHeight(f.i + 1, f.j), VertexHeight(f.i, f.j + 1),
            VertexHeight(f.i + 1, f.j + 1), &f);
  return f.h00 + f.u * f.dzdu + f.v * f.dzdv;
}

double Terrain::GridHeight(int i, int j) const {
  return TileOfCell(std::min(i, cols_ - 2), std::min(j, rows_ - 2)).Height(i, j);
}

double Terrain::Height(double x, double y) const {
  const Facet f = FacetAt(x, y);
  return f.h00 + f.u * f.dzdu + f.v * f.dzdv;
}

GroundSample Terrain::Sample(double x, double y) const {
  const Facet f = FacetAt(x, y);
  GroundSample s;
  s.height_m = f.h00 + f.u * f.dzdu + f.v * f.dzdv;
  s.normal = Eigen::Vector3d(-f.dzdu / cell_, -f.dzdv / cell_, 1.0).normalized();
  s.material = &materials_[f.tile->CellMaterial(f.i, f.j)];
  return s;
}

const TerrainMaterial& Terrain::MaterialAt(double x, double y) const {
  return *Sample(x, y).material;
}

SoilPoint Terrain::SoilAt(const TerrainMaterial& material, double x, double y) const {
  assert(&material >= materials_.data() && &material < materials_.data() + materials_.size());
  const SoilPoint& base = soils_[static_cast<std::size_t>(&material - materials_.data())];
  return soil_variation_.Apply(base, x, y);
}

}  // namespace trackbed::sim
