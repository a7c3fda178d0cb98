// Headless rendering of the world on OSMesa (Mesa's llvmpipe, no display, no
// GPU): the same geometry the physics uses — the terrain triangulation,
// walls, boxes, cylinders, the triangles of mesh objects with their files'
// images — plus visual-only dressing (tree crowns, a
// ceiling, doors and posters), textured procedurally from the seed and lit by
// a directional light plus ambient. One OpenGL context per renderer, reused
// for every frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/render/image.h"
#include "trackbed/render/pinhole.h"
#include "trackbed/render/procedural_texture.h"
#include "trackbed/render/robot_shadow.h"
#include "trackbed/render/scene_lighting.h"
#include "trackbed/render/sky.h"
#include "trackbed/sim/occluder.h"
#include "trackbed/sim/track_marks.h"
#include "trackbed/sim/world.h"

namespace trackbed::render {

class TrackMarkDrawing;

/// Light and dressing of a scene.
/// How the ground's materials look (docs/rendering.md): `classic`, each material's
/// texture repeated tile after tile; `detailed`, each tile of a material takes a variant
/// of its texture, turned, mirrored and shifted from the seed (no period).
enum class GroundLook { kClassic, kDetailed };

/// How a tree's crown is drawn (docs/rendering.md): `spheres`, a faceted sphere with the
/// `leaves` texture; `leaves`, a cloud of leaf cards (leaf_crown.h).
enum class CrownLook { kSpheres, kLeaves };

struct SceneAppearance {
  /// Direction the sunlight comes from: azimuth counter-clockwise from +x [deg].
  double sun_azimuth_deg = 135.0;
  /// Elevation of the sun above the horizon [deg], in (0, 90].
  double sun_elevation_deg = 50.0;
  /// Ambient light level [0, 1].
  double ambient = 0.45;
  /// Directional light level [0, 1].
  double diffuse = 0.6;
  /// Grey level of the background (sky) [0, 1]; under a clear or cloudy sky, the
  /// horizon's 90° from the sun.
  double sky_gray = 0.85;
  /// How the sky looks (sky.h): flat (`sky_gray`), clear or cloudy.
  SkyLook sky = SkyLook::kFlat;
  /// Height of a ceiling over the whole terrain [m]; 0 for none (outdoors).
  double ceiling_height_m = 0.0;
  /// Foliage crowns on objects of kind "tree" (visual only).
  bool tree_crowns = true;
  /// How the crowns are drawn: spheres, or leaf cards (leaf_crown.h).
  CrownLook crowns = CrownLook::kSpheres;
  /// Side of the square procedural textures [px], a power of two in [16, 2048].
  int texture_size_px = 256;
  /// Distance from the detail centre within which the terrain is drawn from its
  /// full grid [m]; beyond it, blended to every 2nd vertex by 1.5×, every 4th
  /// from 2× to 3×, every 8th from 4× to 6× this distance (TerrainDetail). 0: the
  /// full grid everywhere.
  double terrain_full_detail_m = 0.0;
  /// Trees drawn with fewer facets where that moves their silhouette by less than
  /// this many pixels, judged from the detail centre (object_detail.h) [px]. 0:
  /// every object at full detail.
  double object_far_error_px = 0.0;
  /// The ground's look: classic (a period of one texture tile) or detailed.
  GroundLook ground_look = GroundLook::kClassic;
  /// Materials that keep the classic look under `detailed` (names with a texture).
  std::vector<std::string> classic_look_materials;
  /// Light that changes across the scene: shadows and lit zones (scene_lighting.h).
  /// Absent: the whole scene is lit alike.
  std::optional<SceneLighting> lighting;
  /// The robot's own shadow from the sun, drawn each frame at its pose (robot_shadow.h).
  bool robot_shadow = false;
  /// The robot's own track marks on deformable ground, drawn only (sim/track_marks.h);
  /// absent: none.
  std::optional<sim::TrackMarkOptions> track_marks;

  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("sun_azimuth_deg", &sun_azimuth_deg);
    a->Visit("sun_elevation_deg", &sun_elevation_deg);
    a->Visit("ambient", &ambient);
    a->Visit("diffuse", &diffuse);
    a->Visit("sky_gray", &sky_gray);
    a->Visit("ceiling_height_m", &ceiling_height_m);
    a->Visit("tree_crowns", &tree_crowns);
    a->VisitEnum("crowns", &crowns,
                 {{"spheres", CrownLook::kSpheres}, {"leaves", CrownLook::kLeaves}});
    a->Visit("texture_size_px", &texture_size_px);
    a->Visit("terrain_full_detail_m", &terrain_full_detail_m);
    a->Visit("object_far_error_px", &object_far_error_px);
    a->VisitEnum("ground_look", &ground_look,
                 {{"classic", GroundLook::kClassic}, {"detailed", GroundLook::kDetailed}});
    a->Visit("classic_look_materials", &classic_look_materials, archive::kOmitEmpty);
    a->Visit("lighting", &lighting, archive::kOmitEmpty);
    a->Visit("robot_shadow", &robot_shadow);
    a->Visit("track_marks", &track_marks, archive::kOmitEmpty);
    a->VisitEnum(
        "sky", &sky,
        {{"flat", SkyLook::kFlat}, {"clear", SkyLook::kClear}, {"cloudy", SkyLook::kCloudy}});
  }
};

/// Renders grayscale and depth images of a World. Not copyable.
class Renderer {
 public:
  /// Builds the context, the textures and the geometry for images of
  /// `width_px` × `height_px`, depth clipped to [near_m, far_m], geometry's edges
  /// drawn at `edge_samples` samples a pixel (1 or 4; docs/rendering.md, "Antialiased
  /// edges"). Throws std::invalid_argument for bad sizes or sample counts,
  /// std::runtime_error when OSMesa cannot make a context.
  Renderer(const sim::World& world, const SceneAppearance& appearance,
           std::vector<sim::OccluderSpec> occluders, std::uint64_t seed, int width_px,
           int height_px, double near_m, double far_m, int edge_samples = 1);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders the view of a camera with intrinsics `K` (its size must be the
  /// renderer's) at pose `T_world_camera` (OpenCV camera axes) at simulation
  /// time `t_s` (for the occluders). Either output may be null. The terrain's
  /// detail is measured from `detail_center_xy` (world x, y [m]), or from the
  /// camera when it is null: pass one point for both cameras of a stereo pair
  /// so that they see the same ground.
  void Render(const geometry::PinholeCamera& K, const Eigen::Isometry3d& T_world_camera, double t_s,
              GrayImage* gray, DepthImage* depth,
              const Eigen::Vector2d* detail_center_xy = nullptr);

  /// Whether the output is pre-exposed: with scene lighting, the light is multiplied by
  /// the exposure (SetExposure) before the 8-bit output clips, as a sensor saturates;
  /// without it, the output is the scene at exposure 1 and the caller scales it.
  bool pre_exposed() const;

  /// Triangles of mesh objects the last Render() submitted (chunks in view, at the
  /// version drawn: docs/rendering.md, "mesh objects").
  std::size_t mesh_triangles_submitted() const;

  /// The exposure the following renders are pre-exposed for (relative light, > 0).
  /// Throws std::logic_error without scene lighting.
  void SetExposure(double exposure);

  /// Draws every surface of `appearance` (a texture or terrain material name) with
  /// `texture` from now on, in place of its procedural one: a calibration target. No
  /// effect when no surface has that appearance. Throws std::invalid_argument when its
  /// meters_per_repeat is not the procedural one's (the meshes are scaled by it).
  void ReplaceTexture(const std::string& appearance, const Texture& texture);

  /// The boxes of the robot (its body frame) whose shadow the sun casts when the
  /// appearance's `robot_shadow` is set; none by default. Throws std::invalid_argument
  /// for more than kMaxShadowBoxes or a size not > 0.
  void SetRobotShape(std::vector<ShadowBox> boxes_body);
  /// Where the robot is for the following renders (its body frame in the world).
  void SetRobotPose(const Eigen::Isometry3d& T_world_body);
  /// The record of the robot's track marks to draw over the ground from now on (it must
  /// outlive the renderer or the next call); null (the default): none.
  void SetTrackMarks(const sim::TrackMarks* marks);

  /// OpenGL renderer and version strings, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) / 4.5
  /// (Compatibility Profile) Mesa 22.3.6".
  std::string gl_description() const;

 private:
  struct Gl;
  std::unique_ptr<Gl> gl_;
  std::unique_ptr<TrackMarkDrawing> track_marks_;
};

}  // namespace trackbed::render
