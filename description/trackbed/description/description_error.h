// The error of a user's robot or world description that cannot be used.
#pragma once

#include <stdexcept>

namespace trackbed::description {

/// An SDF world or a URDF robot that cannot be read or mapped; the message names the
/// file and the element (docs/gazebo_users.md).
class DescriptionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Whether this build reads SDF worlds and URDF robots (CMake option TRACKBED_WITH_SDF).
bool CanReadDescriptions();

}  // namespace trackbed::description
