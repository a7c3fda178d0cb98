// Digital elevation models read from users' files through GDAL, into the world frame
// of a scenario's `scene.terrain.dem` (docs/user_files.md).
//
// Only native pixels are read: the heights between them are the project's own
// (sim::ElevationGrid), so that they do not depend on GDAL's or PROJ's version. The
// file must carry a projected coordinate system in metres, north-up; its pixels may
// be areas or points (GeoTIFF's PixelIsArea and PixelIsPoint, an ASCII grid's
// xllcorner and xllcenter): either way a height belongs to its pixel's centre.
// Coordinates are re-centred on the options' origin in double precision before
// anything becomes a float.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "trackbed/sim/elevation_grid.h"
#include "trackbed/sim/terrain.h"

namespace trackbed::assets {

/// A user's file that cannot be used; the message names the file and what is wrong.
class AssetError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Whether this build reads elevation models (CMake option TRACKBED_WITH_GDAL).
bool CanReadDems();

/// The GDAL drivers an elevation model may be read with: local raster formats only.
const char* const* DemDrivers();

/// What a DEM file holds, read without its heights, in the world frame of the options.
struct DemHeader {
  int cols = 0, rows = 0;           ///< Pixels across and down.
  Eigen::Vector2d first_m, last_m;  ///< World x, y of the outermost pixel centres [m].
  Eigen::Vector2d spacing_m;        ///< Pixel size along x and y [m].
  std::string driver;               ///< GDAL's short name of the format.
  std::string coordinate_system;    ///< The projected system's name.
  bool pixel_is_point = false;      ///< The file's pixels are points (else areas).
  /// Every file the model is read from: the raster and its side files (a
  /// projection's .prj, a world file, GDAL's .aux.xml), as GDAL lists them.
  std::vector<std::string> files;
};

/// Reads the header of `options.file`. Throws AssetError naming the file if it cannot
/// be opened with DemDrivers(), is a network or virtual path, has no or a rotated
/// geotransform, or no projected coordinate system in metres.
DemHeader ReadDemHeader(const sim::DemOptions& options);

/// The heights of the pixels whose centres surround the box `extent_m` (world x_min,
/// y_min, x_max, y_max), one more pixel on each side where the file has it, less the
/// height at the origin (bilinear in the pixels around it); `height_at_origin_m`
/// receives that height if not null. Throws AssetError (naming the file) where the
/// file does not cover the box or the origin, or a needed pixel has no data.
std::shared_ptr<const sim::ElevationGrid> ReadDem(const sim::DemOptions& options,
                                                  const Eigen::Vector4d& extent_m,
                                                  double* height_at_origin_m = nullptr);

}  // namespace trackbed::assets
