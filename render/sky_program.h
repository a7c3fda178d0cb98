// The program that draws the sky (trackbed/render/sky.h). Private to the renderer.
//
// One quad over the whole view at the far plane, drawn after the opaque surfaces and
// before the outlines' fringes: the depth test (less or equal, the buffer cleared to the
// far plane) passes it only where nothing was drawn, it writes no depth, and the fringes
// then blend over the sky. Each fragment shades its own view direction.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstdint>

#include <Eigen/Core>

#include "trackbed/common/pinhole_camera.h"
#include "trackbed/render/sky.h"

namespace trackbed::render {

class SkyProgram {
 public:
  /// Compiles the program for `look` (clear or cloudy) in the current context, its
  /// clouds from `seed`. Throws std::runtime_error when the driver cannot.
  SkyProgram(SkyLook look, std::uint64_t seed);
  SkyProgram(const SkyProgram&) = delete;
  SkyProgram& operator=(const SkyProgram&) = delete;

  /// Draws the sky where nothing was drawn: `view` maps world to OpenGL eye coordinates,
  /// `sun` the unit vector towards the sun in the world, `gray` the horizon's grey 90°
  /// from the sun, `exposure` scales it (1 without a light map), `K` the camera.
  void Draw(const Eigen::Matrix4d& view, const Eigen::Vector3d& sun, double gray, double exposure,
            const geometry::PinholeCamera& K) const;

 private:
  GLuint program_ = 0;
  GLint world_from_eye_ = -1, sun_ = -1, gray_ = -1, ray_from_window_ = -1;
};

}  // namespace trackbed::render
