// Fuzzes teach maps on disk (teach_map.h): the input up to its first NUL byte is map.json,
// the rest patches.bin (absent without a NUL byte) — after features.bin when the rest
// starts with its magic (TBFEATS1), as long as its header's count says — written into a
// temporary map folder (one per process, rewritten for each input) whose key_images/
// holds four 32x24 grey PNGs written once at start-up (milestones 0-3 of a map whose
// camera is 32x24). A map that loads is saved into a second folder and loaded again. The
// map is also loaded on demand and every milestone's features read from its files.
//
// Finding: a crash, a sanitizer report, a hang or an out-of-memory, an exception other
// than std::runtime_error from LoadTeachMap or LoadFeatures, a loaded map that cannot be
// saved and loaded again, or features read on demand that differ from those loaded whole.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

#include <opencv2/imgcodecs.hpp>

#include "fuzz_support.h"
#include "trackbed/teach_repeat/teach_map.h"

namespace {

namespace fs = std::filesystem;
namespace tr = trackbed::teach_repeat;

[[noreturn]] void Finding(const std::string& what) {
  trackbed::fuzz::Finding("teach_map_fuzz", what);
}

// This process's map folders, removed at exit.
struct MapDirs : trackbed::fuzz::ScratchDir {
  fs::path map = path / "map";
  fs::path saved = path / "saved";
  MapDirs() : ScratchDir("teach_map") {
    fs::create_directories(map / "key_images");
    cv::Mat image(24, 32, CV_8UC1);
    for (int k = 0; k < 4; ++k) {
      cv::randu(image, 0, 256);
      char name[32];
      std::snprintf(name, sizeof name, "%06d.png", k);
      if (!cv::imwrite((map / "key_images" / name).string(), image)) {
        Finding("cannot write key images");
      }
    }
  }
};

void Write(const fs::path& path, const std::string& bytes) {
  trackbed::fuzz::WriteFile("teach_map_fuzz", path, bytes);
}

// A feature file at the front of `rest`: its header and the records its count says, as
// far as `rest` goes; taken off `rest`.
std::string TakeFeatures(std::string* rest) {
  std::uint64_t count = 0;
  for (int i = 0; i < 8 && 16 + i < static_cast<int>(rest->size()); ++i) {
    count |= static_cast<std::uint64_t>(static_cast<unsigned char>((*rest)[16 + i])) << (8 * i);
  }
  const bool whole = rest->size() < 24 || count > (rest->size() - 24) / 40;
  const std::size_t bytes = whole ? rest->size() : 24 + 40 * count;
  std::string features = rest->substr(0, bytes);
  rest->erase(0, bytes);
  return features;
}

// The map in `dir` loaded on demand, every milestone's features read, compared with
// `whole` (the map loaded at once, when it loaded).
void LoadOnDemand(const fs::path& dir, const tr::TeachMap* whole) {
  tr::TeachMap lazy;
  try {
    lazy = tr::LoadTeachMap(dir.string(), tr::MapLoading::kOnDemand);
    for (tr::Milestone& m : lazy.milestones) tr::LoadFeatures(&m);
  } catch (const std::runtime_error&) {
    return;
  }
  if (whole == nullptr) return;
  if (lazy.milestones.size() != whole->milestones.size()) Finding("on demand: other milestones");
  for (std::size_t k = 0; k < lazy.milestones.size(); ++k) {
    const auto &a = lazy.milestones[k].features, &b = whole->milestones[k].features;
    if (a.size() != b.size()) Finding("on demand: other feature counts");
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].first_px != b[i].first_px || a[i].last_px != b[i].last_px ||
          a[i].p_first != b[i].p_first || cv::norm(a[i].patch, b[i].patch, cv::NORM_INF) != 0) {
        Finding("on demand: other features");
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const MapDirs dirs;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  Write(dirs.map / "map.json", input.substr(0, nul));
  std::error_code ec;
  fs::remove(dirs.map / "features.bin", ec);
  if (nul != std::string::npos) {
    std::string rest = input.substr(nul + 1);
    if (rest.compare(0, 8, "TBFEATS1") == 0) Write(dirs.map / "features.bin", TakeFeatures(&rest));
    Write(dirs.map / "patches.bin", rest);
  } else {
    fs::remove(dirs.map / "patches.bin", ec);
  }
  tr::TeachMap map;
  try {
    map = tr::LoadTeachMap(dirs.map.string());
  } catch (const std::runtime_error&) {
    LoadOnDemand(dirs.map, nullptr);
    return 0;
  }
  LoadOnDemand(dirs.map, &map);
  try {
    tr::SaveTeachMap(map, dirs.saved.string());
    const tr::TeachMap again = tr::LoadTeachMap(dirs.saved.string());
    if (again.feature_count() != map.feature_count()) Finding("saved map reads back differently");
  } catch (const std::exception& e) {
    Finding(std::string("loaded map does not save and load again: ") + e.what());
  }
  return 0;
}
