// Gazebo sensor blocks read through sdformat (private to trackbed::description; see
// trackbed/description/sensor_blocks.h).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "trackbed/description/sensor_blocks.h"

namespace trackbed::description {

/// A `<sensor>` of a URDF's `<gazebo reference="LINK">` block: the link (empty for a
/// block without a reference) and the sensor element's XML text.
struct GazeboSensorText {
  std::string link;
  std::string xml;
};

/// Every `<gazebo>` block's `<sensor>` elements in URDF text, in file order (none when
/// the text is not XML: urdfdom reports that).
std::vector<GazeboSensorText> GazeboSensors(const std::string& urdf_text);

/// Maps one `<sensor>` element (its XML text, SDF 1.6 as Gazebo reads URDF blocks) at
/// the frame `T_root_frame` it is attached to: the first camera into `out->camera`,
/// the first ray or lidar into `out->range`; the rest, and what of them has no key,
/// into `unmapped`, each entry starting with `where`. `com_root` is the centre of mass
/// in the root's frame (mounts are from it). Throws DescriptionError starting with
/// `where` with sdformat's errors.
void MapSensorText(const std::string& xml, const std::string& where,
                   const Eigen::Isometry3d& T_root_frame, const Eigen::Vector3d& com_root,
                   SensorBlocks* out, std::vector<std::string>* unmapped);

}  // namespace trackbed::description
