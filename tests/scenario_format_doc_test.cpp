// docs/scenario_format.md against the format itself: every key a scenario is written
// with (the defaults, every shipped scene and calibration run, each resolved) is
// documented, and no key is documented under a section whose map no longer has it.
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/common/archive.h"
#include "trackbed/scenario/key_aliases.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::scenario {
namespace {

namespace fs = std::filesystem;

// Every documented key: in a table whose header is `| Key |`, a row's backquoted names
// in its first column, joined to the `### `section`` heading above the table
// (`| `max_wheel_speed_radps` |` under `### `navigation`` is
// navigation.max_wheel_speed_radps).
std::set<std::string> DocumentedKeys(const fs::path& md) {
  std::ifstream in(md);
  const std::regex heading(R"(^#{3,4} `([^`]+)`)"), other_heading(R"(^#{1,4} )");
  const std::regex name("`([^`]+)`");
  std::set<std::string> keys;
  std::string section, line;
  bool in_section = false, key_table = false;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, heading)) {
      section = m[1];
      in_section = true;
    } else if (std::regex_search(line, other_heading)) {
      section.clear();
      in_section = line.rfind("### Top level", 0) == 0;
    } else if (line.rfind("| Key |", 0) == 0) {
      key_table = true;
    } else if (line.rfind("|", 0) != 0) {
      key_table = false;
    } else if (in_section && key_table && line.rfind("| `", 0) == 0) {
      const std::string first = line.substr(1, line.find('|', 1) - 1);
      for (std::sregex_iterator it(first.begin(), first.end(), name), end; it != end; ++it) {
        keys.insert(section.empty() ? (*it)[1].str() : section + "." + (*it)[1].str());
      }
    }
  }
  return keys;
}

// The dotted paths of every value in `node` (list items' keys without their index).
void WrittenKeys(const archive::Node& node, const std::string& path, std::set<std::string>* out) {
  if (node.IsMap()) {
    for (const auto& [key, child] : node.entries())
      WrittenKeys(child, archive::JoinKey(path, key), out);
  } else if (node.IsList() && node.size() > 0 && node.items()[0].IsMap()) {
    for (const archive::Node& item : node.items()) WrittenKeys(item, path, out);
  }
  if (!path.empty()) out->insert(path);
}

// Whether `key` or a map on its way is documented (a map documented as one value).
bool Documented(const std::string& key, const std::set<std::string>& documented) {
  for (std::size_t dot = 0; dot != std::string::npos; dot = key.find('.', dot + 1)) {
    if (dot > 0 && documented.count(key.substr(0, dot))) return true;
  }
  return documented.count(key) > 0;
}

std::set<std::string> KeysOfEveryShippedScenario() {
  std::set<std::string> keys;
  Scenario every_optional;  // the keys written only when set
  every_optional.robot.calibration_dir = "calibration";
  every_optional.robot.as_built_seed = 1;
  every_optional.drive.script.resize(2);  // a body twist, then track speeds
  every_optional.drive.script[1].track_speeds = true;
  WrittenKeys(archive::Write(every_optional), "", &keys);
  const fs::path scenes = fs::path(TRACKBED_SOURCE_DIR) / "scenes";
  for (const auto& entry : fs::recursive_directory_iterator(scenes)) {
    if (entry.path().extension() != ".yaml" || entry.path().parent_path().filename() == "sweeps") {
      continue;
    }
    const Scenario s =
        WithRealismResolved(WithBuiltinMaterialsResolved(LoadScenario(entry.path().string())));
    WrittenKeys(archive::Write(s), "", &keys);
  }
  return keys;
}

TEST(ScenarioFormatDocTest, EveryWrittenKeyIsDocumented) {
  const std::set<std::string> documented =
      DocumentedKeys(fs::path(TRACKBED_SOURCE_DIR) / "docs/scenario_format.md");
  for (const std::string& key : KeysOfEveryShippedScenario()) {
    EXPECT_TRUE(Documented(key, documented)) << key << " is not in docs/scenario_format.md";
  }
}

// A documented key that no scenario is written with, though the map it belongs to is:
// a key that is gone (or one documented under the wrong section). Scene objects have a
// file form of their own, by type, whose optional keys are written only when they
// differ from the type's: they are not checked here.
TEST(ScenarioFormatDocTest, NoDocumentedKeyIsGoneFromItsMap) {
  const std::set<std::string> written = KeysOfEveryShippedScenario();
  for (const std::string& key :
       DocumentedKeys(fs::path(TRACKBED_SOURCE_DIR) / "docs/scenario_format.md")) {
    const std::size_t dot = key.rfind('.');
    if (dot == std::string::npos || key.find('<') != std::string::npos) continue;
    if (key.rfind("scene.objects.", 0) == 0) continue;
    if (!written.count(key.substr(0, dot)) || written.count(key)) continue;
    const auto inside = written.lower_bound(key + ".");
    if (inside != written.end() && inside->rfind(key + ".", 0) == 0) continue;
    ADD_FAILURE() << key << " is documented but no scenario has it";
  }
}

// The rows `| `old` | `new` |` of the page's "Keys that moved" table.
std::set<std::pair<std::string, std::string>> DocumentedAliases(const fs::path& md) {
  std::ifstream in(md);
  const std::regex row(R"(^\| `([^`]+)` \| `([^`]+)` \|)");
  std::set<std::pair<std::string, std::string>> aliases;
  std::string line;
  bool in_section = false;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) in_section = line == "### Keys that moved";
    std::smatch m;
    if (in_section && std::regex_search(line, m, row)) aliases.emplace(m[1], m[2]);
  }
  return aliases;
}

TEST(ScenarioFormatDocTest, KeysThatMovedAreTheAliases) {
  std::set<std::pair<std::string, std::string>> aliases;
  for (const KeyAlias& a : ScenarioKeyAliases()) aliases.emplace(a.old_key, a.new_key);
  EXPECT_EQ(DocumentedAliases(fs::path(TRACKBED_SOURCE_DIR) / "docs/scenario_format.md"), aliases);
}

}  // namespace
}  // namespace trackbed::scenario
