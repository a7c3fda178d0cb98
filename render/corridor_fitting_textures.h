// The textures of the corridor fittings (corridor_fitting_textures.cpp; the fittings
// themselves: sim/corridor_fittings.h): skirting, door frames, switch plates, ceiling
// lights, radiators, notice boards and fire extinguishers. Grey = 255 × reflectance, as
// every texture. Private to the renderer; procedural_texture.cpp registers them.
#pragma once

#include <cstdint>

namespace trackbed::render {

namespace texture_blocks {
struct Field;
}

/// Metres per repeat of the fittings' textures [m]: the switch plate's is the plate
/// (80 mm), the notice board's its width (0.9 m), the others 1 m.
inline constexpr double kSwitchPlateTileM = 0.08;
inline constexpr double kBoardTileM = 0.9;
inline constexpr double kFittingTileM = 1.0;

/// Flat vinyl skirting, reflectance 0.15 (authored: a dark grey skirting).
void Skirting(texture_blocks::Field& f, std::uint64_t seed);
/// A painted steel door frame, reflectance 0.5 (authored: a mid-grey coat).
void DoorFrame(texture_blocks::Field& f, std::uint64_t seed);
/// A white switch plate (0.85) with its 55 mm rocker outlined by a 1 mm shadow gap
/// (authored).
void SwitchPlate(texture_blocks::Field& f, std::uint64_t seed);
/// An opal LED panel's diffuser, 0.99 (white; drawn at the scene's full light).
void Luminaire(texture_blocks::Field& f, std::uint64_t seed);
/// A profiled panel radiator in RAL 9016 traffic white (Purmo's datasheet colour,
/// reflectance 0.85, authored from its lightness): a vertical water channel every 50 mm,
/// shaded on one side and lit on the other (authored).
void Radiator(texture_blocks::Field& f, std::uint64_t seed);
/// A cork notice board (0.35, a granular mottle) in a 20 mm aluminium frame (0.6),
/// 0.9 × 0.6 m from the tile's corner (the tile 0.9 m, the rest frame), holding three to five ISO
/// 216 A4 sheets (210 × 297 mm, paper 0.85) printed with lines of text (grey 0.3, 3 mm high every
/// 6 mm) (reflectances authored).
void NoticeBoard(texture_blocks::Field& f, std::uint64_t seed);
/// A fire extinguisher's body: signal red RAL 3000 (EN 3-7: red bodies), reflectance 0.1
/// as a grey (authored from its luminance), with a white instruction label (0.8) 0.15 m
/// high a quarter of a metre around, from 0.1 m.
void Extinguisher(texture_blocks::Field& f, std::uint64_t seed);

}  // namespace trackbed::render
