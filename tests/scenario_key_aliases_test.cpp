// Moved scenario keys: an old key in a file or a --set override reads as its new path,
// giving both is an error that names the old key, and every alias of the format reads
// like the key it stands for.
#include "trackbed/scenario/key_aliases.h"

#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scenario_key_walk.h"
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

// Each alias, in a file and through --set, with a value other than the default (the
// first of the walk's values the new key takes), reads as its new key; the old key is
// not written; both names at once are an error at the old key.
TEST(KeyAliasesTest, EveryAliasReadsAsItsNewKeyInFilesAndOverrides) {
  constexpr char kMinimal[] = "drive:\n  waypoints: [[0, 0], [5, 0]]\n";
  const archive::Node defaults = archive::Write(ParseScenario(kMinimal, "test.yaml"));
  for (const KeyAlias& alias : ScenarioKeyAliases()) {
    SCOPED_TRACE(alias.old_key);
    EXPECT_EQ(key_walk::NodeAt(defaults, alias.old_key), nullptr) << "the old key is written";
    const archive::Node* now = key_walk::NodeAt(defaults, alias.new_key);
    ASSERT_NE(now, nullptr) << "the new key is not a key of the format";
    std::optional<std::string> by_new;
    std::string value;
    for (const std::string& v : key_walk::OtherValues(*now, "walk_rules.fll")) {
      try {
        by_new = ScenarioToYaml(ParseScenario(kMinimal, "t", {{alias.new_key, v}}));
        value = v;
        break;
      } catch (const ScenarioError&) {
      }
    }
    ASSERT_TRUE(by_new.has_value()) << "no other value tried is valid";
    EXPECT_NE(*by_new, ScenarioToYaml(ParseScenario(kMinimal, "t")));
    EXPECT_EQ(ScenarioToYaml(ParseScenario(kMinimal, "t", {{alias.old_key, value}})), *by_new);
    // In a file: the old key's value where the old key was; then both names.
    archive::Node file = archive::ParseYaml(kMinimal);
    std::string where;
    archive::Reach(file, *archive::ParsePath(alias.old_key), &where) = archive::ParseYaml(value);
    EXPECT_EQ(ScenarioToYaml(ParseScenario(archive::ToYaml(file), "old.yaml")), *by_new);
    archive::Reach(file, *archive::ParsePath(alias.new_key), &where) = archive::ParseYaml(value);
    try {
      ParseScenario(archive::ToYaml(file), "both.yaml");
      ADD_FAILURE() << "old and new key together read";
    } catch (const ScenarioError& e) {
      EXPECT_EQ(e.key(), alias.old_key);
    }
  }
}

}  // namespace
}  // namespace trackbed::scenario
