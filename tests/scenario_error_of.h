// The message a scenario's parse throws: the tests of a key's errors compare it.
#pragma once

#include <string>

#include "trackbed/scenario/scenario_yaml.h"

namespace trackbed::scenario::test {

/// The message ParseScenario throws for `text`, read as the file "test.yaml"; empty
/// when it does not throw.
inline std::string ErrorOf(const std::string& text) {
  try {
    ParseScenario(text, "test.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

}  // namespace trackbed::scenario::test
