// Corridor fittings (`scene.fittings`): what an institutional corridor shows besides
// plain painted walls — skirting boards, door frames, light switches, ceiling lights,
// radiators, notice boards and fire extinguishers — placed along the walls of a scene
// from the seed, each at a size from a cited source (docs/rendering.md, "Corridor
// fittings").
//
// The fittings hang on the walls' faces that look onto the robot's route: every
// object of kind `wall` (a box) gives the long face on the side of its nearest route
// point. Along that face other walls (at corners) and doors block stretches; the
// skirting runs along what remains, a frame surrounds each door with a switch beside
// it, and radiators, notice boards and extinguishers are placed one per `*_spacing_m`
// of face, each at a seeded place in its share of the face, dropped where it would
// meet a door, a poster or another fitting. Ceiling lights hang along the route at
// `light_spacing_m`. Flat fittings are visual-only (`collides` false); radiators and
// extinguishers stand out of the wall and are obstacles.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "trackbed/sim/static_object.h"

namespace trackbed::sim {

/// Sizes and mounting heights of the fittings [m] and the sources they come from
/// (docs/rendering.md lists them with the same sources).
namespace fitting_size {
/// Skirting board: 100 mm high, 15 mm thick (authored: a flat institutional
/// skirting of vinyl or rubber, the upper end of the 60-100 mm profiles on offer).
inline constexpr double kSkirtingHeightM = 0.10;
inline constexpr double kSkirtingThicknessM = 0.015;
/// Door frame (a steel surround frame): a 60 mm face, standing 50 mm out of the wall
/// (10 mm beyond the scene's 40 mm door leaves) (authored: steel surround frames'
/// faces are 50-60 mm).
inline constexpr double kFrameFaceM = 0.06;
inline constexpr double kFrameDepthM = 0.05;
/// Light switch: an 80 × 80 mm plate, 12 mm deep (authored: the plate of European
/// flush-mounted switch ranges), its centre 1.05 m above the floor and 0.15 m beside
/// the door frame (DIN 18015-3:2016, the preferred mounting height and distance from
/// a door).
inline constexpr double kSwitchPlateM = 0.08;
inline constexpr double kSwitchDepthM = 0.012;
inline constexpr double kSwitchCentreHeightM = 1.05;
inline constexpr double kSwitchBesideFrameM = 0.15;
/// Ceiling light: a recessed 600 × 600 mm LED panel (authored: the 600 mm module of
/// suspended-ceiling luminaires), its diffuser 20 mm below the ceiling.
inline constexpr double kLuminaireSideM = 0.6;
inline constexpr double kLuminaireDepthM = 0.02;
/// Panel radiator, type 22 (two panels, two convector sheets): 600 mm high (Purmo
/// Plan Ventil Compact datasheet: heights 300, 500, 600, 900 mm), a length drawn from
/// 0.8, 1.0, 1.2 and 1.4 m (its lengths run 500-2000 mm), 100 mm deep, 40 mm off
/// the wall on its brackets and 100 mm above the floor (authored).
inline constexpr double kRadiatorHeightM = 0.6;
inline constexpr double kRadiatorDepthM = 0.10;
inline constexpr double kRadiatorWallGapM = 0.04;
inline constexpr double kRadiatorFloorGapM = 0.10;
inline constexpr double kRadiatorLengthsM[] = {0.8, 1.0, 1.2, 1.4};
/// Notice board: 0.9 × 0.6 m cork in an aluminium frame, 20 mm deep, its centre
/// 1.5 m above the floor (authored: a common board size at eye height), holding ISO
/// 216 A4 sheets (210 × 297 mm; the texture, docs/rendering.md).
inline constexpr double kBoardWidthM = 0.9;
inline constexpr double kBoardHeightM = 0.6;
inline constexpr double kBoardDepthM = 0.02;
inline constexpr double kBoardCentreHeightM = 1.5;
/// Fire extinguisher: a 6 kg powder extinguisher, 160 mm across and 0.55 m high
/// (authored from EN 3 extinguishers of that charge), 30 mm off the wall on its
/// bracket, its handle (the top) 1.0 m above the floor (ASR A2.2: handle height
/// 0.80-1.20 m).
inline constexpr double kExtinguisherRadiusM = 0.08;
inline constexpr double kExtinguisherHeightM = 0.55;
inline constexpr double kExtinguisherWallGapM = 0.03;
inline constexpr double kExtinguisherTopM = 1.0;
/// Free wall kept between a placed fitting and a door, poster, other fitting or corner.
inline constexpr double kFittingGapM = 0.3;
}  // namespace fitting_size

/// `scene.fittings`: which fittings a corridor gets and how far apart.
struct CorridorFittings {
  /// Skirting boards along the walls' feet, broken by doors (visual-only).
  bool skirting = true;
  /// A frame around each door on a fitted face (visual-only).
  bool door_frames = true;
  /// A light switch beside each door, on a side drawn from the seed (visual-only).
  bool switches = true;
  /// Ceiling lights along the route (needs scene.appearance.ceiling_height_m > 0).
  bool ceiling_lights = true;
  /// Light to light along the route [m], > 0: 2.5 m, the luminaires' height above the
  /// corridor's reference plane, its floor (EN 12464-1:2021: corridors 100 lx at floor
  /// level; ERCO's lighting guide: a regular grid of pitch d equal to that height, the
  /// first d/2 from the end).
  double light_spacing_m = 2.5;
  /// Panel radiators on the walls (obstacles).
  bool radiators = true;
  /// Mean wall length per radiator [m], > 0 (authored).
  double radiator_spacing_m = 12.0;
  /// Notice boards with A4 sheets (visual-only).
  bool notice_boards = true;
  /// Mean wall length per notice board [m], > 0 (authored).
  double notice_board_spacing_m = 12.0;
  /// Fire extinguishers on wall brackets (obstacles).
  bool extinguishers = true;
  /// Mean wall length per extinguisher [m], > 0: 20 m (ASR A2.2: no more than 20 m to
  /// walk to the nearest extinguisher).
  double extinguisher_spacing_m = 20.0;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("skirting", &skirting);
    a->Visit("door_frames", &door_frames);
    a->Visit("switches", &switches);
    a->Visit("ceiling_lights", &ceiling_lights);
    a->Visit("light_spacing_m", &light_spacing_m);
    a->Visit("radiators", &radiators);
    a->Visit("radiator_spacing_m", &radiator_spacing_m);
    a->Visit("notice_boards", &notice_boards);
    a->Visit("notice_board_spacing_m", &notice_board_spacing_m);
    a->Visit("extinguishers", &extinguishers);
    a->Visit("extinguisher_spacing_m", &extinguisher_spacing_m);
  }
};

/// The fittings `spec` places on the walls of `objects` (and about their doors and
/// posters) that face `route` (a polyline, at least one point), with the ceiling
/// lights along `route` under a ceiling at `ceiling_height_m` (> 0 when
/// spec.ceiling_lights). Deterministic in `stream_seed`; mounting heights are above
/// each wall's base (0 where it is not given: a flat floor at z = 0).
std::vector<StaticObject> CorridorFittingObjects(const CorridorFittings& spec,
                                                 const std::vector<StaticObject>& objects,
                                                 const std::vector<Eigen::Vector2d>& route,
                                                 double ceiling_height_m,
                                                 std::uint64_t stream_seed);

}  // namespace trackbed::sim
