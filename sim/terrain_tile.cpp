// Terrain tiles and the cache that generates and drops them (see terrain_tile.h).
#include "trackbed/sim/terrain_tile.h"

#include <stdexcept>

#include "trackbed/common/least_recently_used.h"

namespace trackbed::sim {

TerrainTileCache::TerrainTileCache(std::size_t capacity) : capacity_(capacity) {
  if (capacity_ < 1) throw std::invalid_argument("TerrainTileCache: capacity must be >= 1");
}

const std::shared_ptr<const TerrainTile>& TerrainTileCache::Get(int ti, int tj,
                                                                const Generate& generate) {
  const auto key = std::make_pair(ti, tj);
  auto it = tiles_.find(key);
  if (it == tiles_.end()) {
    if (tiles_.size() >= capacity_) tiles_.erase(LeastRecentlyUsed(tiles_));
    it = tiles_.emplace(key, Entry{std::make_shared<const TerrainTile>(generate(ti, tj)), 0}).first;
    ++generated_;
  }
  it->second.used = ++clock_;
  return it->second.tile;
}

}  // namespace trackbed::sim
