// The shader program that draws a scene with baked light (scene_lighting.h): the
// fixed-function pipeline's ambient and sun (per vertex), with the sun's direct light
// shadowed and the whole scaled by the light map's gain, read per fragment at the
// fragment's world x, y, then by the exposure. Private to the renderer.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <Eigen/Core>

#include "trackbed/render/scene_lighting.h"

namespace trackbed::render {

class LitProgram {
 public:
  /// Compiles the program and uploads `map` in the current context. Throws
  /// std::runtime_error when the driver cannot.
  LitProgram(const LightMap& map, double ambient, double diffuse);
  LitProgram(const LitProgram&) = delete;
  LitProgram& operator=(const LitProgram&) = delete;

  /// Draws with the program until End: `view` maps world to OpenGL eye coordinates,
  /// `sun` is the unit vector towards the sun in the world.
  void Begin(const Eigen::Matrix4d& view, const Eigen::Vector3d& sun, double exposure) const;
  /// Back to the fixed-function pipeline.
  void End() const;

 private:
  GLuint program_ = 0, light_texture_ = 0;
  GLint world_from_eye_ = -1, sun_eye_ = -1, exposure_ = -1;
};

}  // namespace trackbed::render
