// A build without GDAL (TRACKBED_WITH_GDAL=OFF): a scenario that names an elevation
// model gets an error saying so (see dem_reader.h).
#include "trackbed/assets/dem_reader.h"

namespace trackbed::assets {

namespace {

[[noreturn]] void Unavailable(const sim::DemOptions& o) {
  throw AssetError(o.file +
                   ": this trackbed was built without GDAL, which reads elevation models "
                   "(configure with -DTRACKBED_WITH_GDAL=ON, libgdal-dev installed)");
}

constexpr const char* kNoDrivers[] = {nullptr};

}  // namespace

bool CanReadDems() { return false; }

const char* const* DemDrivers() { return kNoDrivers; }

DemHeader ReadDemHeader(const sim::DemOptions& options) { Unavailable(options); }

std::shared_ptr<const sim::ElevationGrid> ReadDem(const sim::DemOptions& options,
                                                  const Eigen::Vector4d&, double*) {
  Unavailable(options);
}

}  // namespace trackbed::assets
