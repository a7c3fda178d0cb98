// FNV-1a of a texture's texels: the pinned-bytes tests' fingerprint of a recipe.
#pragma once

#include <cstdint>

#include "trackbed/render/procedural_texture.h"

namespace trackbed::render::test {

inline std::uint64_t TexelChecksum(const Texture& t) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const std::uint8_t v : t.texels) {
    h ^= v;
    h *= 1099511628211ULL;
  }
  return h;
}

}  // namespace trackbed::render::test
