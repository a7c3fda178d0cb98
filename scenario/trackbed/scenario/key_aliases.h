// Scenario keys that moved: a file or a `--set` override may still use the old dotted
// path, which reads as the new one. Run folders' scenario.yaml is written with the new
// paths only (docs/scenario_format.md, "Keys that moved").
#pragma once

#include <string>
#include <vector>

#include "trackbed/common/archive.h"

namespace trackbed::scenario {

/// One moved key: `old_key` reads as `new_key`. Both are dotted paths of map keys
/// (no list indices); a key inside `old_key` (`old_key.x`) moves along with it.
struct KeyAlias {
  std::string old_key;
  std::string new_key;
};

/// Every moved key of the scenario format.
const std::vector<KeyAlias>& ScenarioKeyAliases();

/// Whether the dotted `key` is `prefix` or lies inside it (`prefix.x`, `prefix[2]`).
bool KeyWithin(const std::string& key, const std::string& prefix);

/// `dotted` with an aliased prefix replaced by its new path (`a.b[2].c` under an
/// alias `a.b` → `x.y` gives `x.y[2].c`); `dotted` itself when no alias covers it.
std::string CurrentKey(const std::string& dotted, const std::vector<KeyAlias>& aliases);

/// Moves the value of every old key present in `root` to its new path, creating the
/// maps on the way (beside what a map there already holds). Throws archive::Error at the
/// old key when the new path is given too ("is the old name of <new>; give only one"),
/// or when the new path cannot be reached.
void MoveAliasedKeys(archive::Node* root, const std::vector<KeyAlias>& aliases);

}  // namespace trackbed::scenario
