// docs/scenario_format.md against the format itself: every key a scenario is written
// with (the defaults, every shipped scene and calibration run, each resolved) is
// documented, and no key is documented under a section whose map no longer has it.
#include <filesystem>
#include <fstream>
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

// The backquoted names in `text`, in order.
std::vector<std::string> Backquoted(const std::string& text) {
  std::vector<std::string> names;
  for (std::size_t open = text.find('`'); open != std::string::npos;) {
    const std::size_t close = text.find('`', open + 1);
    if (close == std::string::npos) break;
    names.push_back(text.substr(open + 1, close - open - 1));
    open = text.find('`', close + 1);
  }
  return names;
}

// The table row's cells (`| a | b |` gives a, b), trimmed.
std::vector<std::string> Cells(const std::string& row) {
  std::vector<std::string> cells;
  std::stringstream in(row.substr(1));
  for (std::string cell; std::getline(in, cell, '|');) {
    const std::size_t begin = cell.find_first_not_of(' '), end = cell.find_last_not_of(' ');
    cells.push_back(begin == std::string::npos ? "" : cell.substr(begin, end - begin + 1));
  }
  return cells;
}

// Every documented key: in a table whose header is `| Key |`, a row's backquoted names
// in its first column (and a table of one key's values, headed `| `type` |`, that key),
// joined to the `### `section`` heading above the table
// (`| `max_wheel_speed_radps` |` under `### `navigation`` is
// navigation.max_wheel_speed_radps).
std::set<std::string> DocumentedKeys(const fs::path& md) {
  std::ifstream in(md);
  std::set<std::string> keys;
  std::string section, line;
  bool in_section = false, in_table = false, key_table = false;
  while (std::getline(in, line)) {
    if (line.rfind("### `", 0) == 0 || line.rfind("#### `", 0) == 0) {
      section = Backquoted(line).front();
      in_section = true;
    } else if (line.rfind("#", 0) == 0) {
      section.clear();
      in_section = line.rfind("### Top level", 0) == 0;
    } else if (line.rfind("|", 0) != 0) {
      key_table = false;
      in_table = false;
    } else if (!in_table) {  // a table's header: `| Key |`, or a key's values (`| `type` |`)
      in_table = true;
      key_table = line.rfind("| Key |", 0) == 0;
      const std::vector<std::string> named = Backquoted(Cells(line).front());
      if (in_section && !key_table && named.size() == 1) {
        keys.insert(section.empty() ? named[0] : section + "." + named[0]);
      }
    } else if (in_section && key_table && line.rfind("| `", 0) == 0) {
      for (const std::string& name : Backquoted(Cells(line).front())) {
        keys.insert(section.empty() ? name : section + "." + name);
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

// Whether `key` is documented: as a row, as a section with rows of its own, inside a map
// documented as one value (a row such as `goal` with its keys in the row), or under a
// placeholder row of its map.
bool Documented(const std::string& key, const std::set<std::string>& documented) {
  // Whether some documented key lies inside `map` (`map.x`): a section of its own.
  const auto has_section = [&documented](const std::string& map) {
    const auto inside = documented.lower_bound(map + ".");
    return inside != documented.end() && inside->rfind(map + ".", 0) == 0;
  };
  if (documented.count(key) || has_section(key)) return true;
  for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', dot + 1)) {
    const std::string map = key.substr(0, dot);
    if (documented.count(map) && !has_section(map)) return true;
    // A placeholder row (`robot.imperfections.<effect>`) stands for every key of its map.
    const auto placeholder = documented.lower_bound(map + ".<");
    if (placeholder != documented.end() && placeholder->rfind(map + ".<", 0) == 0) return true;
  }
  return false;
}

std::set<std::string> KeysOfEveryShippedScenario() {
  std::set<std::string> keys;
  Scenario every_optional;  // the keys written only when set
  every_optional.robot.calibration_dir = "calibration";
  every_optional.robot.as_built_seed = 1;
  every_optional.drive.script.resize(2);  // a body twist, then track speeds
  every_optional.drive.script[1].track_speeds = true;
  every_optional.scene.appearance.classic_look_materials = {"grass"};
  every_optional.scene.geodetic_origin = sim::GeodeticOrigin{};
  every_optional.scene.appearance.track_marks.emplace();
  WrittenKeys(archive::Write(every_optional), "", &keys);
  const fs::path scenes = fs::path(TRACKBED_SOURCE_DIR) / "scenes";
  for (const auto& entry : fs::recursive_directory_iterator(scenes)) {
    const fs::path folder = entry.path().parent_path().filename();
    if (entry.path().extension() != ".yaml" || folder == "sweeps" || folder == "studies") {
      continue;  // sweep files and study files are not scenarios
    }
    // The example on packaged mesh files needs the files scripts/setup.sh installs.
    if (entry.path().filename() == "mesh_props.yaml" &&
        !fs::exists("/usr/local/share/trackbed/assimp-testmodels/OBJ/spider.obj")) {
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
  std::set<std::pair<std::string, std::string>> aliases;
  std::string line;
  bool in_section = false;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) in_section = line == "### Keys that moved";
    if (!in_section || line.rfind("| `", 0) != 0) continue;
    const std::vector<std::string> cells = Cells(line);
    const std::vector<std::string> old_key = Backquoted(cells[0]), new_key = Backquoted(cells[1]);
    if (old_key.size() == 1 && new_key.size() == 1) aliases.emplace(old_key[0], new_key[0]);
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
