// A build without sdformat and urdfdom (TRACKBED_WITH_SDF=OFF): a scenario that names an
// SDF world or a URDF robot gets an error saying so.
#include <filesystem>

#include "trackbed/description/sdf_world.h"
#include "trackbed/description/urdf_robot.h"

namespace trackbed::description {

namespace {

[[noreturn]] void Unavailable(const std::string& file) {
  throw DescriptionError(file +
                         ": this trackbed was built without sdformat and urdfdom, which read "
                         "SDF worlds and URDF robots (configure with -DTRACKBED_WITH_SDF=ON, "
                         "libsdformat-dev and liburdfdom-dev installed)");
}

}  // namespace

bool CanReadDescriptions() { return false; }

SdfScene ReadSdfWorld(const SdfWorldOptions& options, const std::string&) {
  Unavailable(options.file);
}

SdfScene ReadSdfWorldString(const std::string&, const std::string& source_name,
                            const SdfWorldOptions&, const std::string&) {
  Unavailable(source_name);
}

UrdfRobot ReadUrdfRobot(const UrdfRobotOptions& options) { Unavailable(options.file); }

UrdfRobot ReadUrdfRobotString(const std::string&, const std::string& source_name,
                              const UrdfRobotOptions&) {
  Unavailable(source_name);
}

std::string DefaultShapesDir() {
  return (std::filesystem::temp_directory_path() / "trackbed-shapes").string();
}

}  // namespace trackbed::description
