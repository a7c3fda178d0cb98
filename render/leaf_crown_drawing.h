// Draws leafy tree crowns (trackbed/render/leaf_crown.h). Private to the renderer.
//
// Each crown is a display list of its leaf cards, two-sided quads reading the sprays'
// pictures from one texture array (grey premultiplied by coverage, and coverage; the mip
// chain box-filtered here, so a texel of a coarser level holds the mean coverage over
// its span: the fraction of a pixel's footprint that leaves cover). Three passes, as the
// outlines of curved objects (surface_program.h):
// - core, with the opaque surfaces: the pixels the leaves cover wholly, written with
//   their depth;
// - fringe, after the sky, far to near: the pixels they cover partly, blended over what
//   is behind by the coverage (the depth test keeps them behind nearer leaves' cores);
// - depth: where a fringe pixel is at least half covered, its depth.
// Blended fringes of one crown are not sorted among themselves: where several overlap,
// the coverage they leave is right and the grey is their mix in drawing order.
// Lit by the ambient and the sun's diffuse term on either face, |n . sun|; the light
// map of `scene.appearance.lighting` is not read (the crowns are lit alike).
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "trackbed/sim/static_object.h"

namespace trackbed::render {

class LeafCrowns {
 public:
  enum class Pass { kCore = 0, kFringe = 1, kDepth = 2 };

  /// Compiles the programs and uploads the sprays drawn from `seed` in the current
  /// context, lit by `ambient` and the sun's `diffuse` term. Throws std::runtime_error
  /// when the driver cannot.
  LeafCrowns(std::uint64_t seed, double ambient, double diffuse);
  LeafCrowns(const LeafCrowns&) = delete;
  LeafCrowns& operator=(const LeafCrowns&) = delete;

  /// The display list of the cards of the crown of `tree`, of `radius_m` about the top of
  /// its trunk, laid out from the tree's seed (LeafCrownSeed of `scene_seed`, leaf_crown.h).
  GLuint Compile(const sim::StaticObject& tree, double radius_m, std::uint64_t scene_seed) const;

  /// The frame's view (world to OpenGL eye), the unit vector towards the sun in the
  /// world and the exposure (1 without scene lighting).
  void Begin(const Eigen::Matrix4d& view, const Eigen::Vector3d& sun, double exposure);

  /// Draws `pass` of the crowns of the drawables in `order` (pairs of distance and index
  /// into `drawables`, near to far; the fringe far to near): each drawable's
  /// `leaf_list`, where not 0. Leaves the program that was in use, and face culling as
  /// it was.
  template <class Drawables>
  void Draw(Pass pass, const std::vector<std::pair<double, int>>& order,
            const Drawables& drawables) const {
    const GLint previous = Start(pass);
    const auto draw = [&](int k) {
      const GLuint list = drawables[static_cast<std::size_t>(k)].leaf_list;
      if (list != 0) glCallList(list);
    };
    if (pass == Pass::kFringe) {
      for (auto it = order.rbegin(); it != order.rend(); ++it) draw(it->second);
    } else {
      for (const auto& entry : order) draw(entry.second);
    }
    Finish(previous);
  }

 private:
  GLint Start(Pass pass) const;
  void Finish(GLint previous) const;

  struct Program {
    GLuint program = 0;
    GLint sun_eye = -1, exposure = -1;
  };
  Program programs_[3];
  GLuint texture_ = 0;
  std::vector<double> leaf_area_m2_;  // per spray
  mutable bool cull_ = true;          // face culling as it was at Start
};

}  // namespace trackbed::render
