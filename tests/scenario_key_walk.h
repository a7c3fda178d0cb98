// A walk over a scenario section's keys, for tests that check that every key reaches
// the component it sets: the scalar keys under a section of a written scenario, the
// node at a dotted path, and other values to try for a key.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "trackbed/common/archive.h"

namespace trackbed::key_walk {

/// One scalar key: its dotted path and its value as written.
struct ScalarKey {
  std::string path;
  archive::Node value;
};

/// Appends the scalar leaves of `node` at `path`, descending into maps (lists and nulls
/// are left out).
inline void CollectScalarKeys(const archive::Node& node, const std::string& path,
                              std::vector<ScalarKey>* out) {
  if (node.IsScalar()) {
    out->push_back({path, node});
    return;
  }
  if (!node.IsMap()) return;
  for (const auto& [key, child] : node.entries()) {
    CollectScalarKeys(child, archive::JoinKey(path, key), out);
  }
}

/// The node at a dotted path of map keys inside `root`, or null.
inline const archive::Node* NodeAt(const archive::Node& root, const std::string& dotted) {
  const std::optional<archive::Path> path = archive::ParsePath(dotted);
  if (!path) return nullptr;
  const archive::Node* node = &root;
  for (const archive::PathStep& step : *path) {
    if (step.key.empty()) return nullptr;  // a list index: not walked
    node = node->Find(step.key);
    if (!node) return nullptr;
  }
  return node;
}

/// The scalar keys under `section` (e.g. "estimation") of a written document `root`.
inline std::vector<ScalarKey> ScalarKeysUnder(const archive::Node& root,
                                              const std::string& section) {
  std::vector<ScalarKey> keys;
  if (const archive::Node* node = NodeAt(root, section)) CollectScalarKeys(*node, section, &keys);
  return keys;
}

/// Values other than `scalar`'s (a written node: its tag says its type), in the order to
/// try them until one is valid for the key: a bool's negation; for an integer n, n + 2
/// (odd stays odd), n + 1, n − 1, 2n + 7; for a number x ≠ 0, 1.5x, 0.5x, 0.9x, x + 0.5,
/// for 0, 0.25 and 1; for a string, `string_value`.
inline std::vector<std::string> OtherValues(const archive::Node& scalar,
                                            const std::string& string_value = "other") {
  switch (scalar.tag()) {
    case archive::Node::Tag::kBool:
      return {scalar.text() == "true" ? "false" : "true"};
    case archive::Node::Tag::kInteger: {
      const long long n = archive::ParseSigned(scalar.text()).value_or(0);
      return {std::to_string(n + 2), std::to_string(n + 1), std::to_string(n - 1),
              std::to_string(2 * n + 7)};
    }
    case archive::Node::Tag::kFloat: {
      const double x = archive::ParseDouble(scalar.text()).value_or(0.0);
      if (x == 0.0) return {"0.25", "1"};
      std::vector<std::string> values;
      for (double y : {1.5 * x, 0.5 * x, 0.9 * x, x + 0.5}) {
        values.push_back(archive::FormatDouble(y));
      }
      return values;
    }
    default:
      return {string_value};
  }
}

/// Whether two scalar texts mean the same value (numbers compared as numbers).
inline bool SameScalar(const std::string& a, const std::string& b) {
  if (a == b) return true;
  const std::optional<double> x = archive::ParseDouble(a), y = archive::ParseDouble(b);
  return x && y && *x == *y;
}

}  // namespace trackbed::key_walk
