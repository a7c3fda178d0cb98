// Moved scenario keys (see key_aliases.h).
#include "trackbed/scenario/key_aliases.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace trackbed::scenario {

const std::vector<KeyAlias>& ScenarioKeyAliases() {
  static const std::vector<KeyAlias> aliases = {
      // The estimation section.
      {"estimation.icr_offset_m", "estimation.wheel.icr_offset_m"},
      {"estimation.slip_decay_time_s", "estimation.wheel.slip_decay_time_s"},
      {"estimation.slip_filter_time_s", "estimation.wheel.slip_filter_time_s"},
      {"estimation.fusion_rules", "estimation.fusion.rules_file"},
      {"estimation.fusion_weight_rise_time_s", "estimation.fusion.weight_rise_time_s"},
      {"estimation.vo_max_translation_per_frame_m", "estimation.vo.max_translation_per_frame_m"},
      {"estimation.vo_max_rotation_per_frame_deg", "estimation.vo.max_rotation_per_frame_deg"},
      {"estimation.vo_max_acceleration_mps2", "estimation.vo.max_acceleration_mps2"},
      {"estimation.vo_max_angular_acceleration_dps2",
       "estimation.vo.max_angular_acceleration_dps2"},
      {"estimation.vo_max_gyro_rotation_error_deg", "estimation.vo.max_rotation_prior_error_deg"},
      {"estimation.vo_estimate_disparity_offset", "estimation.vo.estimate_disparity_offset"},
  };
  return aliases;
}

namespace {

// The keys of a dotted path without indices; nothing when it has an index.
std::optional<archive::Path> KeysOf(const std::string& dotted) {
  std::optional<archive::Path> path = archive::ParsePath(dotted);
  if (!path) return std::nullopt;
  for (const archive::PathStep& step : *path) {
    if (step.key.empty()) return std::nullopt;
  }
  return path;
}

// Takes the value at `path` out of `root` (its entry removed from the parent map);
// nothing when the path is not there.
std::optional<archive::Node> Take(archive::Node* root, const archive::Path& path) {
  archive::Node* parent = root;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    parent = parent->IsMap() ? parent->Find(path[k].key) : nullptr;
    if (parent == nullptr) return std::nullopt;
  }
  if (!parent->IsMap()) return std::nullopt;
  std::vector<archive::Node::Entry>& entries = parent->entries();
  const auto it = std::find_if(entries.begin(), entries.end(), [&](const archive::Node::Entry& e) {
    return e.first == path.back().key;
  });
  if (it == entries.end()) return std::nullopt;
  archive::Node value = std::move(it->second);
  entries.erase(it);
  return value;
}

}  // namespace

bool KeyWithin(const std::string& key, const std::string& prefix) {
  if (key.size() <= prefix.size()) return key == prefix;
  return key.compare(0, prefix.size(), prefix) == 0 &&
         (key[prefix.size()] == '.' || key[prefix.size()] == '[');
}

std::string CurrentKey(const std::string& dotted, const std::vector<KeyAlias>& aliases) {
  for (const KeyAlias& alias : aliases) {
    if (KeyWithin(dotted, alias.old_key))
      return alias.new_key + dotted.substr(alias.old_key.size());
  }
  return dotted;
}

void MoveAliasedKeys(archive::Node* root, const std::vector<KeyAlias>& aliases) {
  for (const KeyAlias& alias : aliases) {
    const std::optional<archive::Path> from = KeysOf(alias.old_key);
    const std::optional<archive::Path> to = KeysOf(alias.new_key);
    if (!from || !to) throw archive::Error(alias.old_key, "is not an alias of map keys");
    std::optional<archive::Node> value = Take(root, *from);
    if (!value) continue;
    std::string where;
    archive::Node& target = archive::Reach(*root, *to, &where);
    if (!target.IsNull()) {
      throw archive::Error(alias.old_key, "is the old name of " + alias.new_key +
                                              ", which is given too; give only one");
    }
    target = std::move(*value);
  }
}

}  // namespace trackbed::scenario
