// Command lines of the benchmark programs, parsed with CLI11 as `trackbed`'s is, so each
// program has --help and rejects what it does not know instead of guessing.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace trackbed::bench {

/// Parses the command line into `app`. Returns nullopt to go on, or the status main
/// should return at once: 0 after --help (printed), 2 after a bad command line (CLI11
/// has printed why), the status navigation_study's usage message has always had.
inline std::optional<int> Parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return std::nullopt;
}

/// `--set KEY=VALUE`, repeatable, one value per --set so that scenario files may follow.
inline void AddSetOption(CLI::App& app, std::vector<std::string>* sets) {
  app.add_option("--set", *sets, "Override a scenario key: --set dotted.key=value (repeatable)")
      ->allow_extra_args(false);
}

// Only the programs that read scenario files are built knowing the source folder.
#ifdef TRACKBED_SOURCE_DIR
/// The positional scenario files; ScenarioFilesOrDefault fills in the default.
inline void AddScenarioFiles(CLI::App& app, std::vector<std::string>* files) {
  app.add_option("scenarios", *files,
                 "Scenario files (default: scenes/corridor.yaml and scenes/outdoor.yaml)");
}

/// `files`, or the corridor and outdoor scenes when none were given.
inline std::vector<std::string> ScenarioFilesOrDefault(std::vector<std::string> files) {
  if (files.empty()) {
    files = {TRACKBED_SOURCE_DIR "/scenes/corridor.yaml",
             TRACKBED_SOURCE_DIR "/scenes/outdoor.yaml"};
  }
  return files;
}
#endif

}  // namespace trackbed::bench
