// Command-line arguments shared by the benchmark programs: scenario files
// (default: the corridor and outdoor scenes) and one optional numeric flag.
#pragma once

#include <cstring>
#include <string>
#include <vector>

namespace trackbed::bench {

/// Reads `flag VALUE` into *value (when present) and, when `sets` is given,
/// each `--set KEY=VALUE` into it, and returns the other arguments as scenario
/// files, or the two shipped scenes when there are none.
inline std::vector<std::string> ScenarioFiles(int argc, char** argv, const char* flag,
                                              double* value,
                                              std::vector<std::string>* sets = nullptr) {
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], flag) == 0 && i + 1 < argc) {
      *value = std::stod(argv[++i]);
    } else if (sets && std::strcmp(argv[i], "--set") == 0 && i + 1 < argc) {
      sets->emplace_back(argv[++i]);
    } else {
      files.emplace_back(argv[i]);
    }
  }
  if (files.empty()) {
    files = {TRACKBED_SOURCE_DIR "/scenes/corridor.yaml",
             TRACKBED_SOURCE_DIR "/scenes/outdoor.yaml"};
  }
  return files;
}

}  // namespace trackbed::bench
