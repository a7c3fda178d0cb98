// Scenario files: YAML in, YAML out (docs/scenario_format.md).
//
// The reader is strict: unknown keys, wrong types and out-of-range values are
// rejected with a one-line message `<source>: <dotted.key>: <reason>`, where the
// source is the file, or the `--set key=value` override that introduced the
// bad value. Missing keys keep the structs' defaults. The writer emits every
// key, defaults included, with doubles in their shortest exact form, so
// reading what it wrote gives the same scenario and the same text. Both go through
// the config archive (trackbed/common/archive.h) and the structs' Serialize lists.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "trackbed/scenario/scenario.h"

namespace trackbed::scenario {

/// A command-line override `--set key=value`. `key` is a dotted path
/// (`robot.vehicle.mass_kg`); list entries are indexed as `scene.objects.2.height_m`
/// or `scene.objects[2].height_m`. `value` is parsed as YAML, so it may be a
/// scalar, a flow list (`[[0, 0], [5, 0]]`) or a flow map.
struct Override {
  std::string key;
  std::string value;
};

/// Splits `key=value` at the first '='. Throws std::invalid_argument
/// ("--set: expected key=value, got '…'") when there is no '=', the key is empty
/// or the key is not a dotted path of names and indices.
Override ParseOverride(const std::string& key_equals_value);

/// The `key=value` text ParseOverride reads back as `o`.
std::string OverrideText(const Override& o);

/// A scenario that cannot be read: a missing file, a YAML syntax error, an
/// unknown key, a wrong type or an invalid value.
class ScenarioError : public std::runtime_error {
 public:
  /// Message `source: key: reason`, or `source: reason` when `key` is empty.
  ScenarioError(std::string source, std::string key, std::string reason);

  /// The file path, or `--set key=value` for an override.
  const std::string& source() const { return source_; }
  /// The full dotted key (`scene.objects[1].radius_m`); empty for file-level errors.
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string source_, key_, reason_;
};

/// Reads a scenario file, applies `overrides` in order and validates the
/// result (for a run driven as `drive_source` says). Throws ScenarioError.
Scenario LoadScenario(const std::string& path, const std::vector<Override>& overrides = {},
                      DriveSource drive_source = DriveSource::kScenario);

/// As LoadScenario, from YAML text; `source_name` names it in error messages.
Scenario ParseScenario(const std::string& yaml_text, const std::string& source_name,
                       const std::vector<Override>& overrides = {},
                       DriveSource drive_source = DriveSource::kScenario);

/// The scenario as YAML with every key written (defaults included), in the
/// format ParseScenario reads. Doubles use their shortest exact decimal form, so
/// ScenarioToYaml(ParseScenario(ScenarioToYaml(s))) == ScenarioToYaml(s).
std::string ScenarioToYaml(const Scenario& scenario);

}  // namespace trackbed::scenario
