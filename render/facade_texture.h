// A rendered house front with windows (the `facade` texture; facade_texture.cpp): storeys
// of a residential building, one window per bay, each with its frame, casements, glass,
// sill and, in some, a roller shutter part-way down; plaster between them with rain
// streaks under the sills. Private to the renderer; the tests read the layout.
//
// The texture lies on a box's sides as every box texture does (gl_primitives.h): its
// rows run upwards from the box's foot and its columns along the face from a corner, so
// storeys start at the ground and bays at a corner.
#pragma once

#include <cstdint>

namespace trackbed::render {

namespace texture_blocks {
struct Field;
}

/// Storey height, floor to floor [m]: 3.0 m, the top of residential storey heights
/// (Neufert, "Architects' Data", 3rd ed. 2000: 2.75-3.0 m floor to floor in housing).
inline constexpr double kFacadeStoreyM = 3.0;
/// Bay width, window axis to window axis [m] (authored: one window per 3 m of front).
inline constexpr double kFacadeBayM = 3.0;
/// The tile: two bays across, two storeys up [m].
inline constexpr double kFacadeTileM = 6.0;
/// Window opening [m]: 1.26 × 1.385, an opening of DIN 4172's 12.5 cm modular order
/// (1.25 and 1.375 m nominal plus the 10 mm joint), a common size of German housing.
inline constexpr double kFacadeWindowWidthM = 1.26;
inline constexpr double kFacadeWindowHeightM = 1.385;
/// Sill height above the storey's floor [m]: 0.90 m, above the 0.80 m the
/// Musterbauordnung (§ 38) asks of a window parapet up to 12 m above ground.
inline constexpr double kFacadeSillHeightM = 0.90;
/// Visible frame around each pane, outer frame and sash together [m] (authored: PVC
/// casement profiles of 60-70 mm face width and a 50 mm sash).
inline constexpr double kFacadeFrameM = 0.11;

/// The facade texture over one tile (grey = 255 × reflectance as the other
/// textures): plaster 0.67, frames 0.84, glass 0.19-0.38, shutters 0.59.
void Facade(texture_blocks::Field& f, std::uint64_t seed);

}  // namespace trackbed::render
