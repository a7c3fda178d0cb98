// Fuzzes scenario files and `--set` overrides (scenario_yaml.h).
//
// Input: either YAML scenario text, optionally followed by a line `%%` and then one
// `key=value` override per line; or a first line `@corridor` followed by override lines,
// which are applied to the shipped scenes/corridor.yaml (read once at start-up), so that
// the overrides act on a full scenario. Each override line goes through ParseOverride;
// the ones it accepts are applied by ParseScenario, for a scenario-driven and for an
// externally driven run. A scenario that parses is written back with ScenarioToYaml and
// read again: the header promises that round trip gives the same text.
//
// Finding: a crash, a sanitizer report, a hang, an exception other than
// std::invalid_argument from ParseOverride or ScenarioError from ParseScenario, or a
// round trip that fails or changes the text.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "trackbed/scenario/scenario_yaml.h"

namespace {

using trackbed::scenario::DriveSource;
using trackbed::scenario::Override;
using trackbed::scenario::ScenarioError;

const std::string& Corridor() {
  static const std::string text = [] {
    std::ifstream in(TRACKBED_SOURCE_DIR "/scenes/corridor.yaml", std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in || s.str().empty()) {
      std::fprintf(stderr, "scenario_fuzz: cannot read scenes/corridor.yaml\n");
      std::abort();
    }
    return s.str();
  }();
  return text;
}

[[noreturn]] void Finding(const std::string& what) {
  trackbed::fuzz::Finding("scenario_fuzz", what);
}

std::vector<Override> ParseOverrideLines(const std::string& text) {
  std::vector<Override> overrides;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    try {
      overrides.push_back(trackbed::scenario::ParseOverride(line));
    } catch (const std::invalid_argument&) {
    }
  }
  return overrides;
}

void ParseAndRoundTrip(const std::string& yaml, const std::vector<Override>& overrides,
                       DriveSource drive) {
  std::string written;
  try {
    written =
        ScenarioToYaml(trackbed::scenario::ParseScenario(yaml, "fuzz.yaml", overrides, drive));
  } catch (const ScenarioError&) {
    return;
  }
  try {
    const std::string again =
        ScenarioToYaml(trackbed::scenario::ParseScenario(written, "written.yaml", {}, drive));
    if (again != written) Finding("ScenarioToYaml round trip changed the text:\n" + written);
  } catch (const ScenarioError& e) {
    Finding(std::string("ScenarioToYaml's text does not read back: ") + e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  std::string yaml = input;
  std::vector<Override> overrides;
  static const std::string kCorridor = "@corridor\n";
  if (input.compare(0, kCorridor.size(), kCorridor) == 0) {
    yaml = Corridor();
    overrides = ParseOverrideLines(input.substr(kCorridor.size()));
  } else if (const std::size_t sep = input.find("\n%%\n"); sep != std::string::npos) {
    yaml = input.substr(0, sep + 1);
    overrides = ParseOverrideLines(input.substr(sep + 4));
  }
  ParseAndRoundTrip(yaml, overrides, DriveSource::kScenario);
  ParseAndRoundTrip(yaml, overrides, DriveSource::kExternal);
  return 0;
}
