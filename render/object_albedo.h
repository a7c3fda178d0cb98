// Objects given a grey albedo of their own (sim::StaticObject::albedo, an SDF visual's
// colour): drawn as a plain surface of that albedo instead of their appearance's
// texture or a mesh's materials. Private to the renderer.
#pragma once

#include <cstdio>
#include <string>

namespace trackbed::render {

/// The name the renderer keeps the plain texture of `albedo` under; no appearance's
/// name (procedural_texture.h) has a space, so none is taken for it.
inline std::string AlbedoTextureName(double albedo) {
  char name[48];
  std::snprintf(name, sizeof name, "albedo %.9f", albedo);
  return name;
}

}  // namespace trackbed::render
