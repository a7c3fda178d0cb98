// Moved scenario keys: an old key in a file or a --set override reads as its new path,
// giving both is an error that names the old key, and every alias of the format reads
// like the key it stands for.
#include "trackbed/scenario/key_aliases.h"

#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trackbed/common/archive.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::scenario {
namespace {

const std::vector<KeyAlias> kAliases = {{"a.old_leaf", "a.b.leaf"}, {"old_map", "c.new_map"}};

archive::Node Yaml(const std::string& text) { return archive::ParseYaml(text); }

TEST(KeyAliasesTest, CurrentKeyRewritesTheOldPrefixOnly) {
  EXPECT_EQ(CurrentKey("a.old_leaf", kAliases), "a.b.leaf");
  EXPECT_EQ(CurrentKey("old_map.x[2].y", kAliases), "c.new_map.x[2].y");
  EXPECT_EQ(CurrentKey("old_mapping.x", kAliases), "old_mapping.x");
  EXPECT_EQ(CurrentKey("a.old", kAliases), "a.old");
}

TEST(KeyAliasesTest, OldKeysMoveBesideWhatTheNewMapHolds) {
  archive::Node root = Yaml("a: {old_leaf: 3, b: {other: 1}}\nold_map: {x: 1}\nc: {keep: 2}\n");
  MoveAliasedKeys(&root, kAliases);
  EXPECT_EQ(archive::ToJson(root, -1),
            R"({"a":{"b":{"other":1,"leaf":3}},"c":{"keep":2,"new_map":{"x":1}}})");
}

TEST(KeyAliasesTest, OldAndNewKeyTogetherNameTheOldKey) {
  archive::Node root = Yaml("a: {old_leaf: 3, b: {leaf: 4}}\n");
  try {
    MoveAliasedKeys(&root, kAliases);
    FAIL() << "no error";
  } catch (const archive::Error& e) {
    EXPECT_EQ(e.path(), "a.old_leaf");
    EXPECT_EQ(e.reason(), "is the old name of a.b.leaf, which is given too; give only one");
  }
}

TEST(KeyAliasesTest, NothingMovesWithoutOldKeys) {
  archive::Node root = Yaml("a: {b: {leaf: 4}}\n");
  MoveAliasedKeys(&root, kAliases);
  EXPECT_EQ(archive::ToJson(root, -1), R"({"a":{"b":{"leaf":4}}})");
}

// The value the default scenario writes at a dotted key of map keys.
const archive::Node* DefaultAt(const archive::Node& root, const std::string& dotted) {
  const archive::Node* node = &root;
  const std::optional<archive::Path> path = archive::ParsePath(dotted);
  for (const archive::PathStep& step : *path) {
    node = node->Find(step.key);
    if (node == nullptr) return nullptr;
  }
  return node;
}

TEST(KeyAliasesTest, EveryAliasReadsAsItsNewKeyInFilesAndOverrides) {
  constexpr char kMinimal[] = "drive:\n  waypoints: [[0, 0], [5, 0]]\n";
  const archive::Node defaults = archive::Write(ParseScenario(kMinimal, "test.yaml"));
  for (const KeyAlias& alias : ScenarioKeyAliases()) {
    SCOPED_TRACE(alias.old_key);
    EXPECT_EQ(DefaultAt(defaults, alias.old_key), nullptr) << "the old key is still written";
    const archive::Node* value = DefaultAt(defaults, alias.new_key);
    ASSERT_NE(value, nullptr) << "the new key is not a key of the format";
    const std::string text = archive::ToJson(*value, -1);
    const std::string by_new =
        ScenarioToYaml(ParseScenario(kMinimal, "t", {{alias.new_key, text}}));
    EXPECT_EQ(ScenarioToYaml(ParseScenario(kMinimal, "t", {{alias.old_key, text}})), by_new);
    // In a file: the old key's value where the old key was.
    archive::Node file = archive::ParseYaml(kMinimal);
    std::string where;
    archive::Reach(file, *archive::ParsePath(alias.old_key), &where) = *value;
    EXPECT_EQ(ScenarioToYaml(ParseScenario(archive::ToYaml(file), "t")), by_new);
  }
}

}  // namespace
}  // namespace trackbed::scenario
