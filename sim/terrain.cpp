// Heightfield terrain: seeded value-noise roughness, material regions, and
// surface queries that match Bullet's triangulation (see terrain.h).
#include "trackbed/sim/terrain.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

#include "trackbed/common/option_error.h"
#include "trackbed/common/split_mix.h"
#include "trackbed/sim/lattice_noise.h"

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

void TerrainOptions::Validate() const {
  if (!(extent_m[2] > extent_m[0] && extent_m[3] > extent_m[1])) {
    throw OptionError("extent_m", "must be [x_min, y_min, x_max, y_max] with max > min");
  }
  option_check::InRange("cell_size_m", cell_size_m, 0.01, 2.0);
  const double cells =
      (extent_m[2] - extent_m[0]) * (extent_m[3] - extent_m[1]) / (cell_size_m * cell_size_m);
  if (cells > 16e6) throw OptionError("cell_size_m", "gives more than 16 million cells");
  option_check::Nested("roughness", roughness);
  for (std::size_t k = 0; k < materials.size(); ++k) {
    option_check::Nested("materials[" + std::to_string(k) + "]", materials[k]);
  }
  option_check::Nested("soil_variation", soil_variation);
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

}  // namespace

Terrain::Terrain(const TerrainOptions& options, std::uint64_t seed)
    : soil_variation_(Validated(options).soil_variation,
                      split_mix::Stream(seed, kSoilVariationStream)) {
  cell_ = options.cell_size_m;
  x0_ = options.extent_m[0];
  y0_ = options.extent_m[1];
  cols_ = static_cast<int>(std::ceil((options.extent_m[2] - x0_) / cell_)) + 1;
  rows_ = static_cast<int>(std::ceil((options.extent_m[3] - y0_) / cell_)) + 1;

  // Heights: two octaves for each of undulation and bumps, then the slope. Each
  // octave is a lattice noise of the seed alone, so a point's height does not
  // depend on the extent (nor, later, on which tile it is computed in).
  const std::uint64_t height_seed = split_mix::Stream(seed, kHeightStream);
  const TerrainRoughness& r = options.roughness;
  const LatticeNoise hills(split_mix::Stream(height_seed, 0), r.undulation_wavelength_m);
  const LatticeNoise hills2(split_mix::Stream(height_seed, 1), r.undulation_wavelength_m / 2.0);
  const LatticeNoise bumps(split_mix::Stream(height_seed, 2), r.bump_wavelength_m);
  const LatticeNoise bumps2(split_mix::Stream(height_seed, 3), r.bump_wavelength_m / 2.0);
  heights_.resize(static_cast<std::size_t>(cols_) * rows_);
  min_h_ = 1e300;
  max_h_ = -1e300;
  for (int j = 0; j < rows_; ++j) {
    for (int i = 0; i < cols_; ++i) {
      const double x = x0_ + i * cell_, y = y0_ + j * cell_;
      double z = r.slope_x * x + r.slope_y * y;
      if (r.undulation_amplitude_m > 0.0) {
        z += r.undulation_amplitude_m * (0.75 * hills(x, y) + 0.25 * hills2(x, y));
      }
      if (r.bump_amplitude_m > 0.0) {
        z += r.bump_amplitude_m * (0.75 * bumps(x, y) + 0.25 * bumps2(x, y));
      }
      heights_[static_cast<std::size_t>(j) * cols_ + i] = z;
      min_h_ = std::min(min_h_, z);
      max_h_ = std::max(max_h_, z);
    }
  }

  // Materials: built-ins, then the scenario's own (which may shadow a built-in).
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
  const std::uint8_t fallback = index_of(options.default_material, "default_material");
  std::vector<std::uint8_t> region_material;
  for (std::size_t k = 0; k < options.regions.size(); ++k) {
    region_material.push_back(
        index_of(options.regions[k].material, "regions[" + std::to_string(k) + "].material"));
  }
  cell_material_.assign(static_cast<std::size_t>(cols_ - 1) * (rows_ - 1), fallback);
  for (int j = 0; j + 1 < rows_; ++j) {
    for (int i = 0; i + 1 < cols_; ++i) {
      const int k = options.RegionAt(x0_ + (i + 0.5) * cell_, y0_ + (j + 0.5) * cell_);
      if (k >= 0) {
        cell_material_[static_cast<std::size_t>(j) * (cols_ - 1) + i] =
            region_material[static_cast<std::size_t>(k)];
      }
    }
  }
}

Terrain::Facet Terrain::FacetAt(double x, double y) const {
  const double gx = std::clamp((x - x0_) / cell_, 0.0, cols_ - 1.0);
  const double gy = std::clamp((y - y0_) / cell_, 0.0, rows_ - 1.0);
  Facet f;
  f.i = std::min(static_cast<int>(gx), cols_ - 2);
  f.j = std::min(static_cast<int>(gy), rows_ - 2);
  f.u = gx - f.i;
  f.v = gy - f.j;
  const std::size_t base = static_cast<std::size_t>(f.j) * cols_ + f.i;
  const double h00 = heights_[base], h10 = heights_[base + 1];
  const double h01 = heights_[base + cols_], h11 = heights_[base + cols_ + 1];
  f.h00 = h00;
  if (f.u >= f.v) {  // triangle (i,j), (i+1,j), (i+1,j+1)
    f.dzdu = h10 - h00;
    f.dzdv = h11 - h10;
  } else {  // triangle (i,j), (i,j+1), (i+1,j+1)
    f.dzdu = h11 - h01;
    f.dzdv = h01 - h00;
  }
  return f;
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
  s.material = &materials_[cell_material_[static_cast<std::size_t>(f.j) * (cols_ - 1) + f.i]];
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
