// The command line's suggestion for a misspelt name (apps/closest_name.h).
#include "closest_name.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace trackbed::apps {
namespace {

TEST(ClosestNameTest, EditDistanceCountsEachEditOnce) {
  EXPECT_EQ(EditDistance("run", "run"), 0u);
  EXPECT_EQ(EditDistance("runn", "run"), 1u);       // deletion
  EXPECT_EQ(EditDistance("rn", "run"), 1u);         // insertion
  EXPECT_EQ(EditDistance("ran", "run"), 1u);        // substitution
  EXPECT_EQ(EditDistance("--jbos", "--jobs"), 1u);  // transposition
  EXPECT_EQ(EditDistance("", "eval"), 4u);
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);  // the textbook pair
}

TEST(ClosestNameTest, SuggestsTheClosestWithinAThirdOfTheWord) {
  const std::vector<std::string> subcommands = {"run",    "eval", "sweep",      "sweep-cell",
                                                "report", "vo",   "export-mcap"};
  EXPECT_EQ(ClosestName("runn", subcommands), "run");
  EXPECT_EQ(ClosestName("evl", subcommands), "eval");
  EXPECT_EQ(ClosestName("sweep-cel", subcommands), "sweep-cell");
  EXPECT_EQ(ClosestName("swep", subcommands), "sweep");
  EXPECT_EQ(ClosestName("reprot", subcommands), "report");
  EXPECT_EQ(ClosestName("xyz", subcommands), std::nullopt);
  EXPECT_EQ(ClosestName("exportmcp", subcommands), "export-mcap");  // 2 edits in 9 letters
  EXPECT_EQ(ClosestName("xport", subcommands), std::nullopt);       // 2 edits in 5
  const std::vector<std::string> options = {"--out", "--seed", "--set", "--help", "-h"};
  EXPECT_EQ(ClosestName("--seeed", options), "--seed");
  EXPECT_EQ(ClosestName("--ot", options), "--out");
  EXPECT_EQ(ClosestName("--sed", options), "--seed");  // "--set" is as close: the first wins
  EXPECT_EQ(ClosestName("--frobnicate", options), std::nullopt);
}

}  // namespace
}  // namespace trackbed::apps
