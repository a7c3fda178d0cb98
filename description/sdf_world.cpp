// SDF worlds through sdformat, mapped onto trackbed's scene (see sdf_world.h and
// docs/gazebo_users.md).
#include "trackbed/description/sdf_world.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <sdf/Collision.hh>
#include <sdf/Console.hh>
#include <sdf/Element.hh>
#include <sdf/Error.hh>
#include <sdf/Heightmap.hh>
#include <sdf/Light.hh>
#include <sdf/Link.hh>
#include <sdf/Model.hh>
#include <sdf/ParserConfig.hh>
#include <sdf/Physics.hh>
#include <sdf/Root.hh>
#include <sdf/Visual.hh>
#include <sdf/World.hh>

#include "sdf_geometry.h"
#include "sdf_material.h"
#include "trackbed/common/units.h"
#include "trackbed/sim/terrain_material.h"

namespace trackbed::description {

namespace fs = std::filesystem;
using ignition::math::Pose3d;

namespace {

// Names in sdformat's XML paths of the elements nothing maps, and why.
struct Unmappable {
  const char* element;
  const char* why;
};
constexpr Unmappable kUnmappable[] = {
    {"plugin", "Gazebo plugins do not run in trackbed"},
    {"actor", "actors are not simulated (scene.occluders walk scripted paths)"},
    {"joint", "joints are not simulated: static models only"},
    {"sensor",
     "a world's sensors are not simulated (the robot's come from robot.description's "
     "<gazebo> sensor blocks, or robot.stereo and robot.range_sensor)"},
    {"population", "populations are not expanded"},
    {"road", "roads are not drawn"},
    {"script", "OGRE material scripts are not read: drawn as plain_paint"},
    {"audio_source", "sound is not simulated"},
    {"projector", "projectors are not drawn"},
    {"particle_emitter", "particle emitters are not drawn"},
    {"wind", "wind is not simulated"},
    {"atmosphere", "the atmosphere is not simulated"},
    {"magnetic_field", "the magnetic field is not simulated"},
};

// Every element nothing maps, found by name anywhere below `e`.
void CollectUnmappable(const sdf::ElementPtr& e, std::vector<std::string>* out) {
  if (!e) return;
  for (sdf::ElementPtr c = e->GetFirstElement(); c; c = c->GetNextElement()) {
    if (!c->GetExplicitlySetInFile()) continue;  // sdformat's defaults, not the user's
    const std::string name = c->GetName();
    bool listed = false;
    for (const Unmappable& u : kUnmappable) {
      if (name == u.element) {
        out->push_back(ElementWhere(c) + ": " + u.why);
        listed = true;
      }
    }
    if (name == "light" && c->Get<std::string>("type") != "directional") {
      out->push_back(ElementWhere(c) + ": only the sun (a directional light) is mapped");
    }
    if (!listed) CollectUnmappable(c, out);
  }
}

std::string ErrorsText(const std::string& source, const sdf::Errors& errors) {
  std::string text;
  for (const sdf::Error& e : errors) {
    if (!text.empty()) text += "; ";
    text += e.FilePath() ? *e.FilePath() : source;
    if (e.LineNumber()) text += ":" + std::to_string(*e.LineNumber());
    if (e.XmlPath()) text += " " + *e.XmlPath();
    text += ": " + e.Message();
  }
  return text;
}

// The folders `model://` URIs are searched in: the options', then the environment's.
std::vector<std::string> SearchPaths(const SdfWorldOptions& options) {
  std::vector<std::string> paths = options.model_paths;
  for (const char* var : {"GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "SDF_PATH"}) {
    const char* value = std::getenv(var);
    if (value == nullptr) continue;
    std::stringstream list(value);
    std::string p;
    while (std::getline(list, p, ':')) {
      if (!p.empty()) paths.push_back(p);
    }
  }
  return paths;
}

bool IsWebUri(const std::string& uri) {
  return uri.rfind("http://", 0) == 0 || uri.rfind("https://", 0) == 0;
}

std::string RefusedWebUri(const std::string& uri) {
  return "a Fuel or web URI is not fetched (" + uri +
         "): download the model and give its folder in scene.sdf.model_paths";
}

Eigen::Isometry3d ToEigen(const Pose3d& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(p.Rot().W(), p.Rot().X(), p.Rot().Y(), p.Rot().Z())
                   .normalized()
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.Pos().X(), p.Pos().Y(), p.Pos().Z());
  return t;
}

// Maps one world after sdformat has read it.
class WorldMapper {
 public:
  WorldMapper(std::string source, const SdfWorldOptions& options, std::string shapes_dir,
              SdfScene* out)
      : source_(std::move(source)),
        paths_(SearchPaths(options)),
        shapes_dir_(std::move(shapes_dir)),
        out_(out) {}

  void Map(const sdf::World& world) {
    CollectUnmappable(world.Element(), &out_->unmapped);
    MapPhysics(world);
    MapGeodeticOrigin(world);
    MapSun(world);
    for (std::uint64_t i = 0; i < world.ModelCount(); ++i) {
      const sdf::Model& m = *world.ModelByIndex(i);
      Pose3d pose;
      Check(m.SemanticPose().Resolve(pose, "world"), m.Element());
      MapModel(m, ToEigen(pose), false);
    }
  }

 private:
  void Check(const sdf::Errors& errors, const sdf::ElementPtr& e) const {
    if (!errors.empty())
      throw DescriptionError(ElementWhere(e) + ": " + ErrorsText(source_, errors));
  }

  void MapPhysics(const sdf::World& world) {
    if (world.PhysicsCount() > 0) out_->physics_step_s = world.PhysicsDefault()->MaxStepSize();
    const sdf::ElementPtr gravity =
        world.Element()->HasElement("gravity") ? world.Element()->GetElement("gravity") : nullptr;
    out_->gravity_explicit = gravity != nullptr && gravity->GetExplicitlySetInFile();
    const ignition::math::Vector3d g = world.Gravity();
    if (g.X() == 0.0 && g.Y() == 0.0 && g.Z() < 0.0) {
      out_->gravity_mps2 = -g.Z();
    } else {
      out_->unmapped.push_back(ElementWhere(world.Element()) + " <gravity>: (" +
                               std::to_string(g.X()) + ", " + std::to_string(g.Y()) + ", " +
                               std::to_string(g.Z()) +
                               ") does not point along -z; trackbed's gravity does");
    }
  }

  // sdformat refuses a surface other than EARTH_WGS84 and a frame other than ENU
  // (sdformat 12's <world_frame_orientation> knows ENU only); what it reads is mapped.
  void MapGeodeticOrigin(const sdf::World& world) {
    const ignition::math::SphericalCoordinates* sc = world.SphericalCoordinates();
    if (sc == nullptr) return;
    sim::GeodeticOrigin o;
    o.latitude_deg = sc->LatitudeReference().Degree();
    o.longitude_deg = sc->LongitudeReference().Degree();
    o.elevation_m = sc->ElevationReference();
    o.heading_deg = sc->HeadingOffset().Degree();
    out_->geodetic_origin = o;
  }

  void MapSun(const sdf::World& world) {
    for (std::uint64_t i = 0; i < world.LightCount(); ++i) {
      const sdf::Light& light = *world.LightByIndex(i);
      if (light.Type() != sdf::LightType::DIRECTIONAL) continue;  // listed as unmapped
      const ignition::math::Vector3d d = light.Direction();
      const double n = d.Length();
      if (out_->sun_azimuth_deg || !(n > 0.0) || !(d.Z() < 0.0)) {
        out_->unmapped.push_back(ElementWhere(light.Element()) +
                                 (out_->sun_azimuth_deg
                                      ? ": a second directional light (the first is the sun)"
                                      : ": a directional light not shining downwards"));
        continue;
      }
      out_->sun_azimuth_deg = units::Degrees(std::atan2(-d.Y(), -d.X()));
      out_->sun_elevation_deg = units::Degrees(std::asin(-d.Z() / n));
    }
  }

  void MapModel(const sdf::Model& model, const Eigen::Isometry3d& T_world_model,
                bool parent_static) {
    const bool is_static = model.Static() || parent_static;
    if (!is_static) {
      out_->unmapped.push_back(ElementWhere(model.Element()) +
                               ": not static (only static models are mapped)");
      return;
    }
    for (std::uint64_t i = 0; i < model.ModelCount(); ++i) {
      const sdf::Model& m = *model.ModelByIndex(i);
      Pose3d pose;
      Check(m.SemanticPose().Resolve(pose, "__model__"), m.Element());
      MapModel(m, T_world_model * ToEigen(pose), true);
    }
    for (std::uint64_t i = 0; i < model.LinkCount(); ++i) {
      MapLink(*model.LinkByIndex(i), T_world_model);
    }
  }

  void MapLink(const sdf::Link& link, const Eigen::Isometry3d& T_world_model) {
    std::vector<GeometryInWorld> collisions;
    for (std::uint64_t i = 0; i < link.CollisionCount(); ++i) {
      const sdf::Collision& c = *link.CollisionByIndex(i);
      Pose3d pose;
      Check(c.SemanticPose().Resolve(pose, "__model__"), c.Element());
      collisions.push_back({c.Geom(), T_world_model * ToEigen(pose), c.Element()});
    }
    std::vector<bool> used(collisions.size(), false);
    for (std::uint64_t i = 0; i < link.VisualCount(); ++i) {
      const sdf::Visual& v = *link.VisualByIndex(i);
      Pose3d pose;
      Check(v.SemanticPose().Resolve(pose, "__model__"), v.Element());
      const GeometryInWorld visual{v.Geom(), T_world_model * ToEigen(pose), v.Element()};
      MapVisual(visual, v, collisions, &used);
    }
    for (std::size_t k = 0; k < collisions.size(); ++k) {
      if (used[k]) continue;
      if (collisions[k].geometry->Type() == sdf::GeometryType::PLANE) {
        MapGround(collisions[k]);
      } else if (collisions[k].geometry->Type() == sdf::GeometryType::HEIGHTMAP) {
        MapHeightmap(collisions[k]);
      } else {
        out_->unmapped.push_back(ElementWhere(collisions[k].element) +
                                 ": a collision no visual of its link draws is not simulated");
      }
    }
  }

  void MapVisual(const GeometryInWorld& visual, const sdf::Visual& v,
                 const std::vector<GeometryInWorld>& collisions, std::vector<bool>* used) {
    int match = -1;
    for (std::size_t k = 0; k < collisions.size() && match < 0; ++k) {
      if (!(*used)[k] && SameGeometry(visual, collisions[k])) match = static_cast<int>(k);
    }
    int collision_file = -1;
    for (std::size_t k = 0; k < collisions.size() && match < 0 && collision_file < 0; ++k) {
      if (!(*used)[k] && MeshCollisionFor(visual, collisions[k])) {
        collision_file = static_cast<int>(k);
      }
    }
    if (visual.geometry->Type() == sdf::GeometryType::PLANE) {
      MapGround(match >= 0 ? collisions[match] : visual);
      if (match >= 0) (*used)[match] = true;
      return;
    }
    if (visual.geometry->Type() == sdf::GeometryType::HEIGHTMAP) {
      MapHeightmap(match >= 0 ? collisions[match] : visual);
      if (match >= 0) (*used)[match] = true;
      return;
    }
    sim::StaticObject object;
    std::string why;
    const GeometryMapping mapping{source_, paths_, shapes_dir_};
    if (!MapShape(mapping, visual, &object, &why)) {
      out_->unmapped.push_back(ElementWhere(visual.element) + ": " + why);
      return;
    }
    if (v.Material() != nullptr) {
      const sdf::GeometryType type = visual.geometry->Type();
      const bool can_pattern = type == sdf::GeometryType::BOX ||
                               type == sdf::GeometryType::CYLINDER ||
                               type == sdf::GeometryType::SPHERE;
      std::optional<AlbedoPattern> pattern;
      object.albedo =
          MaterialAlbedo(mapping, *v.Material(), ElementWhere(v.Element()) + " <material>",
                         can_pattern ? &pattern : nullptr, &out_->unmapped);
      if (pattern)
        MapTexturedShape(mapping, visual, pattern->image_file, pattern->diffuse, &object);
    }
    object.appearance = sim::FindObjectType(object.kind)->appearance;
    object.collides = match >= 0 || collision_file >= 0;
    if (match >= 0) {
      (*used)[match] = true;
      const std::optional<double> mu = FrictionMu(collisions[match].element);
      if (mu) {
        out_->unmapped.push_back(ElementWhere(collisions[match].element) +
                                 " <surface><friction>: mu " + std::to_string(*mu) +
                                 " not mapped: obstacles have no friction key");
      }
    }
    if (collision_file >= 0) {
      (*used)[collision_file] = true;
      object.mesh.collision = sim::MeshSource::Collision::kFile;
      object.mesh.collision_file = MeshFile(mapping, collisions[collision_file]);
    }
    out_->objects.push_back(std::move(object));
  }

  // A heightmap image: the terrain's heights (the first one; Gazebo's conventions in
  // sim::HeightmapOptions), its friction the default material's as a ground plane's.
  void MapHeightmap(const GeometryInWorld& g) {
    const sdf::Heightmap& h = *g.geometry->HeightmapShape();
    const std::string where = ElementWhere(g.element) + " <heightmap>";
    std::string lower = fs::path(h.Uri()).extension().string();
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const Eigen::Vector3d size = ToEigen3(h.Size());
    std::string why;
    if (out_->heightmap) {
      why = "a second heightmap (the first is the terrain)";
    } else if (!g.pose.linear().isIdentity(1e-9)) {
      why = "a turned heightmap (trackbed's terrain grid runs along x and y)";
    } else if (lower == ".tif" || lower == ".tiff" || lower == ".dem" || lower == ".asc" ||
               lower == ".img" || lower == ".hgt") {
      why =
          "an elevation model as a heightmap: give it as scene.terrain.dem (a GeoTIFF with a "
          "projected coordinate system; docs/user_files.md)";
    } else if (!(size.minCoeff() > 0.0)) {
      why = "a heightmap whose <size> is not > 0 (Gazebo inverts the heights for a negative z)";
    }
    if (!why.empty()) {
      out_->unmapped.push_back(where + ": " + why);
      return;
    }
    sim::HeightmapOptions o;
    const GeometryMapping mapping{source_, paths_, shapes_dir_};
    o.file = ResolveUri(mapping, h.Uri(), h.FilePath(), where + "<uri>");
    o.size_m = size;
    o.pos_m = g.pose * ToEigen3(h.Position());
    out_->heightmap = o;
    if (h.TextureCount() > 0 || h.BlendCount() > 0) {
      out_->unmapped.push_back(where +
                               " <texture>, <blend>: the terrain is drawn with its "
                               "materials' textures (scene.terrain.default_material, regions)");
    }
    const std::optional<double> mu = FrictionMu(g.element);
    if (mu) out_->ground_material = NearestMaterial(*mu);
  }

  static std::string NearestMaterial(double mu) {
    const sim::TerrainMaterial* nearest = nullptr;
    for (const sim::TerrainMaterial& m : sim::BuiltinMaterials()) {
      const double d = std::abs(std::tan(units::Radians(m.friction_angle_deg)) - mu);
      if (nearest == nullptr ||
          d < std::abs(std::tan(units::Radians(nearest->friction_angle_deg)) - mu)) {
        nearest = &m;
      }
    }
    return nearest->name;
  }

  // A horizontal plane: the terrain's ground, its friction the default material's.
  void MapGround(const GeometryInWorld& plane) {
    const Eigen::Vector3d n =
        plane.pose.linear() * ToEigen3(plane.geometry->PlaneShape()->Normal()).normalized();
    if (n.z() < 1.0 - 1e-9 || std::abs(plane.pose.translation().z()) > 1e-9) {
      out_->unmapped.push_back(ElementWhere(plane.element) +
                               ": a plane other than the horizontal one through z = 0 (the "
                               "terrain's ground)");
      return;
    }
    const std::optional<double> mu = FrictionMu(plane.element);
    if (mu) out_->ground_material = NearestMaterial(*mu);
  }

  std::string source_;
  std::vector<std::string> paths_;
  std::string shapes_dir_;
  SdfScene* out_;
};

SdfScene MapRoot(sdf::Root& root, const sdf::Errors& errors, const std::string& source,
                 const SdfWorldOptions& options, const std::string& shapes_dir,
                 const std::vector<std::string>& refused) {
  if (!refused.empty()) throw DescriptionError(source + ": " + RefusedWebUri(refused.front()));
  if (!errors.empty()) throw DescriptionError(ErrorsText(source, errors));
  if (root.WorldCount() == 0) throw DescriptionError(source + ": holds no <world>");
  SdfScene scene;
  if (root.WorldCount() > 1) {
    scene.unmapped.push_back(source + ": " + std::to_string(root.WorldCount() - 1) +
                             " worlds after the first");
  }
  WorldMapper(source, options, shapes_dir, &scene).Map(*root.WorldByIndex(0));
  return scene;
}

// The parser's configuration: `model://` searched in the options' and the environment's
// folders; web URIs recorded in `refused` and not fetched.
sdf::ParserConfig Config(const SdfWorldOptions& options, std::vector<std::string>* refused) {
  // The parser's errors come back as sdf::Errors, named in the DescriptionError.
  sdf::Console::Instance()->SetQuiet(true);
  sdf::ParserConfig config;
  for (const std::string& p : SearchPaths(options)) config.AddURIPath("model://", p);
  config.SetFindCallback([refused](const std::string& uri) -> std::string {
    if (IsWebUri(uri)) refused->push_back(uri);
    return "";
  });
  return config;
}

}  // namespace

bool CanReadDescriptions() { return true; }

SdfScene ReadSdfWorld(const SdfWorldOptions& options, const std::string& shapes_dir) {
  if (!fs::is_regular_file(options.file)) {
    throw DescriptionError(options.file + ": no such file");
  }
  std::vector<std::string> refused;
  sdf::Root root;
  const sdf::Errors errors = root.Load(options.file, Config(options, &refused));
  return MapRoot(root, errors, options.file, options, shapes_dir, refused);
}

SdfScene ReadSdfWorldString(const std::string& sdf_text, const std::string& source_name,
                            const SdfWorldOptions& options, const std::string& shapes_dir) {
  std::vector<std::string> refused;
  sdf::Root root;
  const sdf::Errors errors = root.LoadSdfString(sdf_text, Config(options, &refused));
  return MapRoot(root, errors, source_name, options, shapes_dir, refused);
}

std::string DefaultShapesDir() { return (fs::temp_directory_path() / "trackbed-shapes").string(); }

}  // namespace trackbed::description
