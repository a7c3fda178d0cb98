// A run folder as a ROS 2 bag (docs/mcap.md): `run.mcap` (profile ros2, CDR messages,
// ros2msg schemas) and the `metadata.yaml` rosbag2 needs to play the folder, from the
// folder's own files, so that a finished run converts the same way whether it is
// converted at its end (`outputs.mcap`) or later (`trackbed export-mcap RUN_DIR`).
// Topics and frames follow REP-103 and REP-105:
//   /clock                          rosgraph_msgs/msg/Clock, at the ground truth's rate
//   /tf                             map → odom (identity) and odom → base_link (fused)
//   /tf_static                      base_link → the cameras' optical frames, imu_link
//   /ground_truth/odom              nav_msgs/msg/Odometry in map, with the true twist
//   /<estimator>/odom               one per estimate file (wheel_odometry, fused, …)
//   /imu                            sensor_msgs/msg/Imu in imu_link
//   /joint_states                   the sprockets' angles and rates from the encoders
//   /stereo/{left,right}/camera_info  the calibration the stack was given
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace trackbed::runner {

/// What a bag holds: messages per topic.
struct RunBagSummary {
  std::map<std::string, std::uint64_t> messages_per_topic;
  std::uint64_t messages = 0;
};

/// Writes `run_dir`/run.mcap and `run_dir`/metadata.yaml from the folder's files (its
/// scenario.yaml says what the run had). Throws std::runtime_error naming the file and
/// the problem when a file is missing or malformed; what was already in the folder is
/// left as it was.
RunBagSummary WriteRunBag(const std::filesystem::path& run_dir);

}  // namespace trackbed::runner
