// SDF geometries mapped onto scene objects (see sdf_geometry.h).
#include "sdf_geometry.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <sdf/Box.hh>
#include <sdf/Capsule.hh>
#include <sdf/Cylinder.hh>
#include <sdf/Ellipsoid.hh>
#include <sdf/Heightmap.hh>
#include <sdf/Mesh.hh>
#include <sdf/Plane.hh>
#include <sdf/Sphere.hh>

#include "generated_file.h"
#include "textured_unit_shapes.h"
#include "trackbed/description/description_error.h"

namespace trackbed::description {

namespace fs = std::filesystem;

namespace {

constexpr double kSame = 1e-9;  // poses and sizes equal to this [m, -]
constexpr int kSlices = 64;     // around a unit cylinder's and sphere's axis
constexpr int kStacks = 32;     // a unit sphere's bands from pole to pole
constexpr double kPi = 3.14159265358979323846;

bool SamePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm() <= kSame &&
         (a.linear() - b.linear()).norm() <= kSame;
}

bool Near(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm() <= kSame; }

// The unit meshes as PLY text: vertices, then triangles (counter-clockwise outside).
std::string PlyText(const std::vector<Eigen::Vector3d>& v, const std::vector<Eigen::Vector3i>& f) {
  std::ostringstream s;
  s.precision(17);
  s << "ply\nformat ascii 1.0\nelement vertex " << v.size()
    << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << f.size()
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Eigen::Vector3d& p : v) s << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const Eigen::Vector3i& t : f) s << "3 " << t.x() << ' ' << t.y() << ' ' << t.z() << '\n';
  return s.str();
}

std::string UnitBox() {
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i < 8; ++i)
    v.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
  const std::vector<Eigen::Vector3i> f = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                          {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                          {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return PlyText(v, f);
}

std::string UnitCylinder() {
  std::vector<Eigen::Vector3d> v = {{0, 0, -0.5}, {0, 0, 0.5}};
  std::vector<Eigen::Vector3i> f;
  for (int i = 0; i < kSlices; ++i) {
    const double a = 2.0 * kPi * i / kSlices;
    v.emplace_back(std::cos(a), std::sin(a), -0.5);
    v.emplace_back(std::cos(a), std::sin(a), 0.5);
  }
  for (int i = 0; i < kSlices; ++i) {
    const int b0 = 2 + 2 * i, t0 = b0 + 1, b1 = 2 + 2 * ((i + 1) % kSlices), t1 = b1 + 1;
    f.emplace_back(b0, b1, t1);
    f.emplace_back(b0, t1, t0);
    f.emplace_back(0, b1, b0);
    f.emplace_back(1, t0, t1);
  }
  return PlyText(v, f);
}

std::string UnitSphere() {
  std::vector<Eigen::Vector3d> v = {{0, 0, -1}, {0, 0, 1}};
  std::vector<Eigen::Vector3i> f;
  for (int j = 1; j < kStacks; ++j) {
    const double polar = kPi * j / kStacks;
    for (int i = 0; i < kSlices; ++i) {
      const double a = 2.0 * kPi * i / kSlices;
      v.emplace_back(std::sin(polar) * std::cos(a), std::sin(polar) * std::sin(a),
                     -std::cos(polar));
    }
  }
  const auto at = [](int ring, int i) { return 2 + (ring - 1) * kSlices + (i % kSlices); };
  for (int i = 0; i < kSlices; ++i) {
    f.emplace_back(0, at(1, i + 1), at(1, i));
    f.emplace_back(1, at(kStacks - 1, i), at(kStacks - 1, i + 1));
    for (int j = 1; j + 1 < kStacks; ++j) {
      f.emplace_back(at(j, i), at(j, i + 1), at(j + 1, i + 1));
      f.emplace_back(at(j, i), at(j + 1, i + 1), at(j + 1, i));
    }
  }
  return PlyText(v, f);
}

// R = Rz(yaw) · Ry(pitch) · Rx(roll) (sim::RollPitchYaw).
void SetRollPitchYaw(const Eigen::Matrix3d& r, sim::StaticObject* o) {
  o->pitch_rad = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  o->roll_rad = std::atan2(r(2, 1), r(2, 2));
  o->yaw_rad = std::atan2(r(1, 0), r(0, 0));
}

// A unit mesh scaled and placed at the geometry's pose.
void AsUnitMesh(const GeometryMapping& mapping, const GeometryInWorld& g, const char* name,
                const Eigen::Vector3d& scale, sim::StaticObject* o) {
  o->shape = sim::StaticObject::Shape::kMesh;
  o->kind = "mesh";
  o->mesh.file = UnitShapeFile(mapping.shapes_dir, name);
  o->mesh.scale = scale;
  o->center_m = g.pose.translation().head<2>();
  o->base_z_m = g.pose.translation().z();
  SetRollPitchYaw(g.pose.linear(), o);
}

}  // namespace

std::string ElementWhere(const sdf::ElementPtr& e) {
  if (!e) return "?";
  std::string w = e->FilePath().empty() ? std::string("?") : e->FilePath();
  if (e->LineNumber()) w += ":" + std::to_string(*e->LineNumber());
  return w + " " + (e->XmlPath().empty() ? "<" + e->GetName() + ">" : e->XmlPath());
}

std::string UnitShapeFile(const std::string& dir, const std::string& name) {
  const std::string text = name == "box"        ? UnitBox()
                           : name == "cylinder" ? UnitCylinder()
                                                : UnitSphere();
  const fs::path file = fs::path(dir) / ("unit_" + name + ".ply");
  WriteGeneratedFile(file, text, "the unit " + name + " mesh");
  return file.string();
}

bool SameGeometry(const GeometryInWorld& a, const GeometryInWorld& b) {
  const sdf::Geometry& x = *a.geometry;
  const sdf::Geometry& y = *b.geometry;
  if (x.Type() != y.Type() || !SamePose(a.pose, b.pose)) return false;
  switch (x.Type()) {
    case sdf::GeometryType::BOX:
      return Near(ToEigen3(x.BoxShape()->Size()), ToEigen3(y.BoxShape()->Size()));
    case sdf::GeometryType::CYLINDER:
      return std::abs(x.CylinderShape()->Radius() - y.CylinderShape()->Radius()) <= kSame &&
             std::abs(x.CylinderShape()->Length() - y.CylinderShape()->Length()) <= kSame;
    case sdf::GeometryType::SPHERE:
      return std::abs(x.SphereShape()->Radius() - y.SphereShape()->Radius()) <= kSame;
    case sdf::GeometryType::ELLIPSOID:
      return Near(ToEigen3(x.EllipsoidShape()->Radii()), ToEigen3(y.EllipsoidShape()->Radii()));
    case sdf::GeometryType::MESH:
      return x.MeshShape()->Uri() == y.MeshShape()->Uri() &&
             x.MeshShape()->Submesh() == y.MeshShape()->Submesh() &&
             Near(ToEigen3(x.MeshShape()->Scale()), ToEigen3(y.MeshShape()->Scale()));
    case sdf::GeometryType::PLANE:
      return Near(ToEigen3(x.PlaneShape()->Normal()), ToEigen3(y.PlaneShape()->Normal()));
    default:
      return false;
  }
}

bool MeshCollisionFor(const GeometryInWorld& visual, const GeometryInWorld& collision) {
  const sdf::Geometry& v = *visual.geometry;
  const sdf::Geometry& c = *collision.geometry;
  return v.Type() == sdf::GeometryType::MESH && c.Type() == sdf::GeometryType::MESH &&
         SamePose(visual.pose, collision.pose) && c.MeshShape()->Submesh().empty() &&
         Near(ToEigen3(v.MeshShape()->Scale()), ToEigen3(c.MeshShape()->Scale()));
}

std::string ResolveUri(const GeometryMapping& mapping, std::string uri,
                       const std::string& defined_in, const std::string& where) {
  if (uri.rfind("http://", 0) == 0 || uri.rfind("https://", 0) == 0) {
    throw DescriptionError(where + ": a Fuel or web URI is not fetched (" + uri +
                           "): download the model and give its folder in scene.sdf.model_paths");
  }
  if (uri.rfind("model://", 0) == 0) {
    const std::string rest = uri.substr(8);
    std::string searched;
    for (const std::string& p : mapping.paths) {
      const fs::path f = fs::path(p) / rest;
      if (fs::is_regular_file(f)) return fs::absolute(f).lexically_normal().string();
      searched += (searched.empty() ? "" : ", ") + p;
    }
    throw DescriptionError(where + ": " + uri + " is in none of the model paths (" +
                           (searched.empty() ? std::string("none given") : searched) +
                           "; scene.sdf.model_paths, GZ_SIM_RESOURCE_PATH, "
                           "IGN_GAZEBO_RESOURCE_PATH, SDF_PATH)");
  }
  if (uri.rfind("file://", 0) == 0) uri = uri.substr(7);
  fs::path f(uri);
  if (f.is_relative()) {
    f = fs::path(defined_in.empty() ? mapping.source : defined_in).parent_path() / f;
  }
  f = fs::absolute(f).lexically_normal();
  if (!fs::is_regular_file(f)) throw DescriptionError(where + ": no such file: " + f.string());
  return f.string();
}

std::string MeshFile(const GeometryMapping& mapping, const GeometryInWorld& g) {
  const sdf::Mesh& mesh = *g.geometry->MeshShape();
  return ResolveUri(mapping, mesh.Uri(), mesh.FilePath(), ElementWhere(g.element) + " <mesh><uri>");
}

bool MapShape(const GeometryMapping& mapping, const GeometryInWorld& g, sim::StaticObject* o,
              std::string* why) {
  const Eigen::Matrix3d& r = g.pose.linear();
  const Eigen::Vector3d p = g.pose.translation();
  switch (g.geometry->Type()) {
    case sdf::GeometryType::BOX: {
      const Eigen::Vector3d size = ToEigen3(g.geometry->BoxShape()->Size());
      if (r(2, 2) < 1.0 - kSame) {
        AsUnitMesh(mapping, g, "box", size, o);
        return true;
      }
      o->shape = sim::StaticObject::Shape::kBox;
      o->kind = "box";
      o->center_m = p.head<2>();
      o->base_z_m = p.z() - 0.5 * size.z();
      o->yaw_rad = std::atan2(r(1, 0), r(0, 0));
      o->size_m = size;
      return true;
    }
    case sdf::GeometryType::CYLINDER: {
      const double radius = g.geometry->CylinderShape()->Radius();
      const double length = g.geometry->CylinderShape()->Length();
      if (std::abs(r(2, 2)) < 1.0 - kSame) {
        AsUnitMesh(mapping, g, "cylinder", {radius, radius, length}, o);
        return true;
      }
      o->shape = sim::StaticObject::Shape::kCylinder;
      o->kind = "cylinder";
      o->center_m = p.head<2>();
      o->base_z_m = p.z() - 0.5 * length;
      o->radius_m = radius;
      o->height_m = length;
      return true;
    }
    case sdf::GeometryType::SPHERE:
      AsUnitMesh(mapping, g, "sphere",
                 Eigen::Vector3d::Constant(g.geometry->SphereShape()->Radius()), o);
      return true;
    case sdf::GeometryType::ELLIPSOID:
      AsUnitMesh(mapping, g, "sphere", ToEigen3(g.geometry->EllipsoidShape()->Radii()), o);
      return true;
    case sdf::GeometryType::MESH:
      if (!g.geometry->MeshShape()->Submesh().empty()) {
        *why = "a <submesh> of a mesh file is not picked out";
        return false;
      }
      AsUnitMesh(mapping, g, "box", ToEigen3(g.geometry->MeshShape()->Scale()), o);
      o->mesh.file = MeshFile(mapping, g);
      return true;
    case sdf::GeometryType::CAPSULE:
      *why = "a capsule has no shape in trackbed";
      return false;
    case sdf::GeometryType::HEIGHTMAP:
      *why = "a heightmap is the terrain (scene.terrain.heightmap), not an object";
      return false;
    default:
      *why = "an empty or unknown geometry";
      return false;
  }
}

void MapTexturedShape(const GeometryMapping& mapping, const GeometryInWorld& g,
                      const std::string& image_file, const std::array<double, 3>& diffuse,
                      sim::StaticObject* o) {
  const char* name = "sphere";
  Eigen::Vector3d scale;
  if (g.geometry->Type() == sdf::GeometryType::BOX) {
    name = "box";
    scale = ToEigen3(g.geometry->BoxShape()->Size());
  } else if (g.geometry->Type() == sdf::GeometryType::CYLINDER) {
    name = "cylinder";
    const double r = g.geometry->CylinderShape()->Radius();
    scale = {r, r, g.geometry->CylinderShape()->Length()};
  } else {
    scale = Eigen::Vector3d::Constant(g.geometry->SphereShape()->Radius());
  }
  const sim::StaticObject::Shape before = o->shape;
  AsUnitMesh(mapping, g, name, scale, o);
  if (before != sim::StaticObject::Shape::kMesh) {
    // An upright box or cylinder was one of trackbed's own shapes: now a mesh object.
    o->size_m = sim::StaticObject{}.size_m;
    o->radius_m = sim::StaticObject{}.radius_m;
    o->height_m = sim::StaticObject{}.height_m;
  }
  o->mesh.file = TexturedUnitShapeFile(mapping.shapes_dir, name, image_file, diffuse);
}

std::optional<double> FrictionMu(const sdf::ElementPtr& collision) {
  if (!collision || collision->GetName() != "collision" || !collision->HasElement("surface")) {
    return std::nullopt;
  }
  const sdf::ElementPtr surface = collision->FindElement("surface");
  if (!surface->HasElement("friction")) return std::nullopt;
  const sdf::ElementPtr friction = surface->FindElement("friction");
  if (!friction->HasElement("ode")) return std::nullopt;
  const sdf::ElementPtr ode = friction->FindElement("ode");
  if (!ode->HasElement("mu")) return std::nullopt;
  return ode->Get<double>("mu");
}

}  // namespace trackbed::description
