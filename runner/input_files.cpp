// The files a scenario names, fingerprinted (see input_files.h).
#include "trackbed/runner/input_files.h"

#include <algorithm>
#include <iostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "trackbed/assets/dem_reader.h"
#include "trackbed/assets/mesh_reader.h"
#include "trackbed/common/durable_file.h"
#include "trackbed/common/sha256.h"

namespace trackbed::runner {

namespace fs = std::filesystem;

namespace {

// The (key, path) of every file a folder holds, in path order.
void AddFolder(const std::string& key, const std::string& folder,
               std::vector<std::pair<std::string, std::string>>* named) {
  std::vector<std::string> files;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(folder)) {
    if (e.is_regular_file()) files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  for (std::string& f : files) named->emplace_back(key, std::move(f));
}

}  // namespace

std::vector<InputFile> InputFiles(const scenario::Scenario& s) {
  std::vector<std::pair<std::string, std::string>> named;
  if (s.scene.sdf && !s.scene.sdf->file.empty())
    named.emplace_back("scene.sdf.file", s.scene.sdf->file);
  if (s.robot.description && !s.robot.description->file.empty()) {
    named.emplace_back("robot.description.file", s.robot.description->file);
  }
  const sim::DemOptions& dem = s.scene.terrain.dem;
  if (dem.enabled()) {
    for (const std::string& f : assets::ReadDemHeader(dem).files) {
      named.emplace_back("scene.terrain.dem.file", f);
    }
  }
  if (s.scene.terrain.heightmap) {
    named.emplace_back("scene.terrain.heightmap.file", s.scene.terrain.heightmap->file);
  }
  for (std::size_t k = 0; k < s.scene.objects.size(); ++k) {
    const sim::StaticObject& o = s.scene.objects[k];
    if (o.shape != sim::StaticObject::Shape::kMesh) continue;
    const std::string key = "scene.objects[" + std::to_string(k) + "].";
    for (const auto& [name, file] : {std::pair<std::string, std::string>{"file", o.mesh.file},
                                     {"collision_file", o.mesh.collision_file}}) {
      if (file.empty()) continue;
      const std::shared_ptr<const assets::MeshRead> read = assets::ReadMeshKept(file);
      for (const std::string& f : read->files) named.emplace_back(key + name, f);
      for (const std::string& f : read->textures) named.emplace_back(key + name, f);
    }
  }
  if (!s.robot.calibration_dir.empty()) {
    AddFolder("robot.calibration_dir", s.robot.calibration_dir, &named);
  }
  const std::string& rules = s.estimation.localization.fusion.rules_file;
  if (!rules.empty()) named.emplace_back("estimation.fusion.rules_file", rules);
  if (s.teach_repeat.enabled && !s.teach_repeat.map.empty()) {
    AddFolder("teach_repeat.map", s.teach_repeat.map, &named);
  }
  std::vector<InputFile> files;
  std::set<std::string> seen;
  for (const auto& [key, path] : named) {
    if (!seen.insert(path).second) continue;
    InputFile f;
    f.key = key;
    f.path = path;
    f.bytes = fs::file_size(path);
    f.sha256 = Sha256OfFile(path);
    files.push_back(std::move(f));
  }
  return files;
}

void WriteInputsJson(const scenario::Scenario& scenario, const fs::path& dir) {
  const std::vector<InputFile> files = InputFiles(scenario);
  if (files.empty()) return;
  nlohmann::ordered_json j;
  j["files"] = nlohmann::ordered_json::array();
  for (const InputFile& f : files) {
    j["files"].push_back(
        {{"key", f.key}, {"path", f.path}, {"bytes", f.bytes}, {"sha256", f.sha256}});
  }
  WriteFileAtomically(dir / "inputs.json", j.dump(2) + "\n");
}

namespace {

// `entries` one a line in `dir`/`name`, and in one warning line on stderr.
void WriteUnmappedList(const std::string& file, const std::vector<std::string>& entries,
                       const fs::path& dir, const char* name) {
  if (entries.empty()) return;
  std::string text, line;
  for (const std::string& entry : entries) {
    text += entry + "\n";
    line += (line.empty() ? "" : "; ") + entry;
  }
  WriteFileAtomically(dir / name, text);
  std::cerr << "warning: " << file << ": " << entries.size() << " not mapped (" << name
            << "): " << line << "\n";
}

}  // namespace

void WriteUnmapped(const scenario::Scenario& scenario, const fs::path& dir) {
  if (scenario.scene.sdf) {
    WriteUnmappedList(scenario.scene.sdf->file, scenario.scene.sdf->unmapped, dir,
                      "sdf_unmapped.txt");
  }
  if (scenario.robot.description) {
    WriteUnmappedList(scenario.robot.description->file, scenario.robot.description->unmapped, dir,
                      "urdf_unmapped.txt");
  }
}

}  // namespace trackbed::runner
