// Gazebo heightmap images read from users' files through OpenCV, into the world frame
// of a scenario's `scene.terrain.heightmap` (docs/gazebo_users.md, "Heightmaps").
//
// Only the image's pixels are read: the heights between them are the project's own
// (sim::ElevationGrid, bilinear), as for an elevation model (dem_reader.h).
#pragma once

#include <memory>
#include <string>

#include "trackbed/assets/dem_reader.h"
#include "trackbed/sim/elevation_grid.h"
#include "trackbed/sim/terrain.h"

namespace trackbed::assets {

/// The heights of `options.file`'s pixels in the world (sim::HeightmapOptions says
/// where): pixel (c, r), r counted from the image's top row, lies at
/// x = pos.x − size.x/2 + c·size.x/(n − 1), y = pos.y + size.y/2 − r·size.y/(n − 1), at
/// z = pos.z + size.z · v / v_max, v_max the image's brightest value (all black: z =
/// pos.z). Throws AssetError naming the file: not an image OpenCV decodes, not one
/// grey channel of 8 or 16 bits, not square, fewer than 2 × 2 pixels.
std::shared_ptr<const sim::ElevationGrid> ReadHeightmap(const sim::HeightmapOptions& options);

}  // namespace trackbed::assets
