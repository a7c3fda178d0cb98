// SDF geometries mapped onto scene objects (private to trackbed::description): the
// shapes trackbed has (an upright box, an upright cylinder), the unit meshes scaled for
// the others, `model://` and relative mesh URIs resolved.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <ignition/math/Vector3.hh>
#include <sdf/Element.hh>
#include <sdf/Geometry.hh>

#include "trackbed/sim/static_object.h"

namespace trackbed::description {

/// A visual's or a collision's geometry with its pose in the world.
struct GeometryInWorld {
  const sdf::Geometry* geometry = nullptr;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  sdf::ElementPtr element;  ///< The <visual> or <collision>, for errors.
};

/// What mapping a geometry needs besides it.
struct GeometryMapping {
  const std::string& source;              ///< The world's file, for errors.
  const std::vector<std::string>& paths;  ///< Folders `model://` URIs are searched in.
  const std::string& shapes_dir;          ///< Where the unit meshes are written.
};

inline Eigen::Vector3d ToEigen3(const ignition::math::Vector3d& v) { return {v.X(), v.Y(), v.Z()}; }

/// The element in errors and in the unmapped list: its file:line and XML path.
std::string ElementWhere(const sdf::ElementPtr& e);

/// Whether a visual and a collision are the same solid (same shape, size and pose).
bool SameGeometry(const GeometryInWorld& a, const GeometryInWorld& b);
/// Whether `collision` is a mesh at the visual mesh's pose and scale from another file.
bool MeshCollisionFor(const GeometryInWorld& visual, const GeometryInWorld& collision);

/// Maps `g` onto `object`; false with `why` set when trackbed has nothing for it.
/// Throws DescriptionError (naming the element) for a mesh URI it cannot resolve.
bool MapShape(const GeometryMapping& mapping, const GeometryInWorld& g, sim::StaticObject* object,
              std::string* why);

/// Maps a box, cylinder or sphere `g` onto `object` as its unit shape with Gazebo's
/// texture coordinates and the image `image_file` times `diffuse`
/// (textured_unit_shapes.h), a mesh object whatever its pose.
void MapTexturedShape(const GeometryMapping& mapping, const GeometryInWorld& g,
                      const std::string& image_file, const std::array<double, 3>& diffuse,
                      sim::StaticObject* object);

/// The file a mesh geometry's URI names. Throws DescriptionError naming the element for
/// a web URI or a `model://` URI in none of the paths.
std::string MeshFile(const GeometryMapping& mapping, const GeometryInWorld& g);

/// The file a URI names (`model://`, `file://`, absolute, or relative to `defined_in`,
/// the file the element was read from, else the world's). Throws DescriptionError
/// starting with `where` for a web URI, a `model://` URI in none of the paths or a file
/// that is not there.
std::string ResolveUri(const GeometryMapping& mapping, std::string uri,
                       const std::string& defined_in, const std::string& where);

/// A collision's `<surface><friction><ode><mu>`, if given.
std::optional<double> FrictionMu(const sdf::ElementPtr& collision);

/// The unit mesh `name` (box: side 1, cylinder: radius 1 and height 1, sphere: radius 1,
/// each centred on its origin, z up) as a PLY file in `dir`, written if absent.
std::string UnitShapeFile(const std::string& dir, const std::string& name);

}  // namespace trackbed::description
