// The robot's own track marks drawn over the ground (docs/rendering.md, "Track marks"):
// each track's rut from the record (sim/track_marks.h) as a strip over the terrain whose
// program multiplies the ground's grey by how the rut's shape changes the light there —
// its floor and walls, and the grousers' imprints in its floor — each piece lit by the
// scene's sun and sky, averaged over the pixel's footprint in closed form. Private to
// the renderer; needs the renderer's context current.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <vector>

#include <Eigen/Core>

#include "trackbed/sim/track_marks.h"

namespace trackbed::render {

/// The dry sand's angle of repose [rad]: the steepest a rut's wall or a grouser's imprint
/// stands (34°; sands 30–35°, Al-Hashemi & Al-Amoudi 2018, Powder Technol. 330).
inline constexpr double kReposeAngleRad = 34.0 * 3.14159265358979323846 / 180.0;

/// One frame's strip of the marks: corner vertices (world, 3 floats), their mark
/// coordinates (grouser phase in pitches, across [m], rut depth [m], half the track's
/// width [m]) and the across direction (world, 3 floats), 6 vertices a segment.
struct TrackMarkStrip {
  std::vector<float> position, mark, across;
  int vertices() const { return static_cast<int>(position.size() / 3); }
};

/// The segments of `marks` with an end within `reach_m` of `camera_world` (horizontal),
/// each a quad as wide as the rut and its walls plus a margin.
TrackMarkStrip BuildTrackMarkStrip(const sim::TrackMarks& marks,
                                   const Eigen::Vector3d& camera_world, double reach_m);

/// The drawing of one record. Not copyable.
class TrackMarkDrawing {
 public:
  explicit TrackMarkDrawing(const sim::TrackMarks* marks) : marks_(marks) {}
  TrackMarkDrawing(const TrackMarkDrawing&) = delete;
  TrackMarkDrawing& operator=(const TrackMarkDrawing&) = delete;

  /// Multiplies what is drawn of the ground by the marks' light, for a camera at
  /// `camera_world` (the modelview matrix is the view), the sun `sun_world` (unit,
  /// towards it), the light's `ambient` and `diffuse`. Depth untouched.
  void Draw(const Eigen::Vector3d& camera_world, const Eigen::Vector3d& sun_world, double ambient,
            double diffuse);

 private:
  void Link();

  const sim::TrackMarks* marks_;
  GLuint program_ = 0;
  GLint camera_ = -1, sun_ = -1, ambient_ = -1, diffuse_ = -1, pitch_ = -1, grouser_ = -1;
  GLint mark_attrib_ = -1, across_attrib_ = -1;
};

}  // namespace trackbed::render
