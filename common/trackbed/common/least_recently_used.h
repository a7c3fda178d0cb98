// Least-recently-used eviction for the small caches that page the world in tiles (the
// terrain's tiles, the physics' ground pieces): each entry carries a `used` stamp from a
// counter that rises with every use, and the entry with the smallest stamp goes first.
// A linear scan: these caches hold tens of entries.
#pragma once

namespace trackbed {

/// The entry of `entries` (a map whose values have a `used` stamp) used longest ago;
/// entries.end() when it is empty.
template <class Map>
typename Map::iterator LeastRecentlyUsed(Map& entries) {
  auto oldest = entries.begin();
  for (auto it = entries.begin(); it != entries.end(); ++it) {
    if (it->second.used < oldest->second.used) oldest = it;
  }
  return oldest;
}

}  // namespace trackbed
