// SDF worlds read through sdformat (Gazebo's own parser) and mapped onto trackbed's
// scene: static models' boxes, cylinders, spheres, ellipsoids and meshes become scene
// objects, a horizontal ground plane's friction picks the terrain's material, the
// physics step, gravity, the geodetic origin and the sun set the world's and the light's
// keys. What cannot
// be mapped is listed, never dropped in silence (docs/gazebo_users.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "trackbed/description/description_error.h"
#include "trackbed/sim/geodetic_origin.h"
#include "trackbed/sim/static_object.h"
#include "trackbed/sim/terrain.h"

namespace trackbed::description {

/// An SDF world a scenario names (`scene.sdf`).
struct SdfWorldOptions {
  /// The SDF file (.sdf or .world), relative to the scenario's folder; absolute once
  /// the scenario is loaded.
  std::string file;
  /// Folders searched for `model://NAME/…` URIs, in order, before the environment's
  /// GZ_SIM_RESOURCE_PATH, IGN_GAZEBO_RESOURCE_PATH and SDF_PATH; relative to the
  /// scenario's folder.
  std::vector<std::string> model_paths;
  /// Set when the world has been mapped into the scene (a run folder's scenario.yaml
  /// holds the mapped objects, which are not mapped again).
  bool mapped = false;
  /// What the world holds that was not mapped, one entry each (filled when mapped).
  std::vector<std::string> unmapped;

  /// Throws OptionError naming the field: `file` empty.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md), read and
  /// written by the config archive (trackbed/common/archive.h).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("file", &file);
    a->Visit("model_paths", &model_paths);
    a->Visit("mapped", &mapped);
    a->Visit("unmapped", &unmapped);
  }
};

/// What an SDF world maps onto.
struct SdfScene {
  /// The static models' shapes, in the world frame.
  std::vector<sim::StaticObject> objects;
  /// `<physics><max_step_size>` [s], if the world has a physics block.
  std::optional<double> physics_step_s;
  /// The magnitude of `<gravity>` [m/s²] when it points along −z (sdformat's default
  /// 9.8 where the world gives none).
  std::optional<double> gravity_mps2;
  /// Whether the world's file gives `<gravity>` (else gravity_mps2 is sdformat's default).
  bool gravity_explicit = false;
  /// `<spherical_coordinates>`: the world's geodetic origin (WGS 84, East–North–Up
  /// turned by `<heading_deg>`; sdformat refuses other surfaces and frames).
  std::optional<sim::GeodeticOrigin> geodetic_origin;
  /// Where the first directional light comes from (the sun): azimuth counter-clockwise
  /// from +x and elevation [deg].
  std::optional<double> sun_azimuth_deg, sun_elevation_deg;
  /// The first `<heightmap>` (a greyscale image), its file resolved, its pos in the world.
  std::optional<sim::HeightmapOptions> heightmap;
  /// The built-in terrain material whose friction is nearest the ground plane's `<mu>`.
  std::optional<std::string> ground_material;
  /// Everything not mapped, one entry each: what it is, where, and why.
  std::vector<std::string> unmapped;
};

/// Reads `options.file` through sdformat and maps its world (the first one). Unit
/// meshes for the shapes trackbed has no primitive for (a sphere, a tilted cylinder or
/// box) are written once into `shapes_dir`. Throws DescriptionError naming the file and
/// the element: sdformat's errors, a Fuel or web URI, a `model://` URI found in none of
/// the paths, a value out of range.
SdfScene ReadSdfWorld(const SdfWorldOptions& options, const std::string& shapes_dir);

/// As ReadSdfWorld, from SDF text; `source_name` names it in errors and relative URIs
/// are relative to the current folder.
SdfScene ReadSdfWorldString(const std::string& sdf_text, const std::string& source_name,
                            const SdfWorldOptions& options, const std::string& shapes_dir);

/// The folder the unit shape meshes go to: the system's temporary folder's
/// `trackbed-shapes`.
std::string DefaultShapesDir();

}  // namespace trackbed::description
