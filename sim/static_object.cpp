// Static scene objects (see static_object.h).
#include "trackbed/sim/static_object.h"

#include <algorithm>
#include <cmath>

#include "trackbed/common/option_error.h"

namespace trackbed::sim {

void StaticObject::Validate() const {
  if (shape == Shape::kBox) {
    option_check::Positive("size_m[0]", size_m.x());
    option_check::Positive("size_m[1]", size_m.y());
    option_check::Positive("size_m[2]", size_m.z());
  } else if (shape == Shape::kCylinder) {
    option_check::Positive("radius_m", radius_m);
    option_check::Positive("height_m", height_m);
  } else {
    if (mesh.file.empty()) throw OptionError("file", "must name a mesh file");
    for (int k = 0; k < 3; ++k) {
      option_check::Positive(("scale[" + std::to_string(k) + "]").c_str(), mesh.scale[k]);
    }
    if ((mesh.collision == MeshSource::Collision::kFile) == mesh.collision_file.empty()) {
      throw OptionError("collision_file",
                        "names the collision mesh exactly when collision is 'file'");
    }
    option_check::Finite("roll_rad", roll_rad);
    option_check::Finite("pitch_rad", pitch_rad);
  }
  option_check::Finite("center_m[0]", center_m.x());
  option_check::Finite("center_m[1]", center_m.y());
  if (std::isinf(base_z_m)) throw OptionError("base_z_m", "must be finite (or absent)");
  option_check::Finite("yaw_rad", yaw_rad);
  if (albedo && !(*albedo >= 0.0 && *albedo <= 1.0)) {
    throw OptionError("albedo", "must be in [0, 1] (got " + option_check::Describe(*albedo) + ")");
  }
}

const std::vector<ObjectType>& ObjectTypes() {
  static const std::vector<ObjectType> types = {
      {"wall", StaticObject::Shape::kBox, "plain_paint"},
      {"box", StaticObject::Shape::kBox, "plain_paint"},
      {"bench", StaticObject::Shape::kBox, "wood"},
      {"cylinder", StaticObject::Shape::kCylinder, "plain_paint"},
      {"tree", StaticObject::Shape::kCylinder, "bark"},
      {"post", StaticObject::Shape::kCylinder, "metal"},
      {"door", StaticObject::Shape::kBox, "door"},
      {"poster", StaticObject::Shape::kBox, "poster"},
      {"mesh", StaticObject::Shape::kMesh, "mesh"},
      {"car", StaticObject::Shape::kBox, "metal"},
  };
  return types;
}

const ObjectType* FindObjectType(const std::string& name) {
  const std::vector<ObjectType>& types = ObjectTypes();
  const auto it =
      std::find_if(types.begin(), types.end(), [&](const ObjectType& t) { return name == t.name; });
  return it == types.end() ? nullptr : &*it;
}

}  // namespace trackbed::sim
