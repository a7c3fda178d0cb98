// The description options' checks, in every build (with or without sdformat and urdfdom).
#include "trackbed/common/option_error.h"
#include "trackbed/description/sdf_world.h"
#include "trackbed/description/urdf_robot.h"

namespace trackbed::description {

void SdfWorldOptions::Validate() const {
  if (file.empty()) throw OptionError("file", "missing: an SDF world names its file");
}

void UrdfRobotOptions::Validate() const {
  if (file.empty()) throw OptionError("file", "missing: a URDF robot names its file");
}

}  // namespace trackbed::description
