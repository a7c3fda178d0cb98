// The files a scenario names besides itself — an SDF world, a URDF robot, an elevation model with
// its side files, mesh objects' files with their side files and textures, a calibration folder, a
// fusion rule base, a teach map — fingerprinted in the run folder's `inputs.json`, since
// `scenario.yaml` alone no longer reproduces a run that reads them (docs/run_folder.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "trackbed/scenario/scenario.h"

namespace trackbed::runner {

/// One file a run read: the scenario key that named it (or its folder), its path,
/// size and SHA-256.
struct InputFile {
  std::string key;
  std::string path;
  std::uintmax_t bytes = 0;
  std::string sha256;
};

/// Every file the scenario names, a folder's files in path order, each once.
std::vector<InputFile> InputFiles(const scenario::Scenario& scenario);

/// Writes `dir`/inputs.json ({"files": [{key, path, bytes, sha256}, ...]}) when the
/// scenario names any file; writes nothing otherwise.
void WriteInputsJson(const scenario::Scenario& scenario, const std::filesystem::path& dir);

/// When the scenario's SDF world (`scene.sdf`) or URDF robot (`robot.description`)
/// holds things not mapped: writes them to `dir`/sdf_unmapped.txt or urdf_unmapped.txt,
/// one a line, and lists them in one warning line on stderr for each.
void WriteUnmapped(const scenario::Scenario& scenario, const std::filesystem::path& dir);

}  // namespace trackbed::runner
