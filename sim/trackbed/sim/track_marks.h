// The robot's own track marks (`scene.appearance.track_marks`, docs/rendering.md "Track
// marks"): where each track's contact patch passed on a deformable ground, the rut it
// left — its centreline on the ground, the track's heading and width, the rut's depth
// (the sinkage the terramechanics computed) and how far the track had run (the grousers'
// phase). A plain record: the vehicle writes it (robot/tracked_vehicle.h), the renderer
// draws it (render/track_mark_drawing.h); the physics never reads it. Bounded: each
// track holds at most `capacity` points, the oldest dropped first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace trackbed::sim {

/// What the record holds and what the drawing takes of the track's shape.
struct TrackMarkOptions {
  /// Points held per track, oldest dropped first [-], in [2, 10'000'000]. At the default
  /// spacing 100'000 points are the last 2 km of each track.
  int capacity = 100000;
  /// Ground travel of a track between two recorded points [m], in [0.005, 1].
  double spacing_m = 0.02;
  /// Distance between the grousers along the track [m], > 0: the track pitch the
  /// vehicle's road-wheel contact length is computed from (docs/physics.md).
  double grouser_pitch_m = 0.02;
  /// Height of a grouser above the track's face [m], >= 0 (authored; an imprint is no
  /// deeper than the rut, nor steeper than the sand's angle of repose).
  double grouser_height_m = 0.005;

  /// Throws OptionError naming the field.
  void Validate() const;

  /// The scenario file's keys (docs/scenario_format.md), read and written by the config
  /// archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("capacity", &capacity);
    a->Visit("spacing_m", &spacing_m);
    a->Visit("grouser_pitch_m", &grouser_pitch_m);
    a->Visit("grouser_height_m", &grouser_height_m);
  }
};

/// One point of a track's rut: the contact patch's centre as the track passed.
struct TrackMarkPoint {
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();  ///< the centreline on the ground [m]
  float heading_rad = 0.0f;  ///< the track's heading (body x in the ground plane) [rad]
  float depth_m = 0.0f;      ///< the rut's depth: the track's sinkage there [m], > 0
  float width_m = 0.0f;      ///< the track's width [m]
  /// How far the track's surface had run (sprocket angle × radius) [m]: the grousers'
  /// imprints lie where it is a whole number of pitches.
  double travel_m = 0.0;
  /// True where a rut begins: the point before it (if any) is not joined to it.
  bool starts_rut = true;
};

/// Both tracks' ruts, each a ring of at most `capacity` points. Not thread-safe: written
/// between renders. Deterministic: the same calls give the same points.
class TrackMarks {
 public:
  /// Throws std::invalid_argument (an OptionError) for invalid options.
  explicit TrackMarks(const TrackMarkOptions& options);

  /// One physics step of track `side` (0 left, 1 right): its contact centre on the
  /// ground `p_world`, heading, width, travel and the rut's depth under it (0 or less:
  /// rigid ground or no contact, which ends the rut). Records a point when the track has
  /// moved `spacing_m` on the ground since the last one, or where a rut begins.
  void Update(int side, const Eigen::Vector3d& p_world, double heading_rad, double depth_m,
              double width_m, double travel_m);

  /// Points held for `side`, oldest first: `size(side)` of them.
  std::size_t size(int side) const;
  const TrackMarkPoint& point(int side, std::size_t i) const;
  /// Points recorded since the start, held or dropped.
  std::uint64_t recorded(int side) const;
  /// Bytes the record holds however long the run: both rings at capacity.
  std::size_t capacity_bytes() const;
  /// Counts every change, so that a drawing knows when to rebuild.
  std::uint64_t version() const { return version_; }
  const TrackMarkOptions& options() const { return options_; }

 private:
  struct Ring {
    std::vector<TrackMarkPoint> points;  // grows to capacity, then overwrites
    std::size_t head = 0;                // the oldest point once full
    std::uint64_t recorded = 0;
    bool open = false;  // the last point's rut goes on
  };
  void Push(Ring* ring, const TrackMarkPoint& p);

  TrackMarkOptions options_;
  Ring rings_[2];
  std::uint64_t version_ = 0;
};

}  // namespace trackbed::sim
