// `trackbed image-stats` (see image_stats_command.h).
#include "image_stats_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "command_errors.h"
#include "trackbed/common/archive.h"
#include "trackbed/common/option_error.h"
#include "trackbed/perception/image_sequence_statistics.h"
#include "trackbed/perception/image_statistics.h"

namespace trackbed::apps {
namespace {

namespace fs = std::filesystem;

struct ImageStatsArguments {
  std::vector<std::string> folders;
  perception::ImageSelection selection;
  perception::ImageStatisticsOptions options;
  std::string json_file, csv_file;
};

struct Measured {
  std::string folder;  // as given
  perception::FolderStatistics statistics;
};

// One printed statistic: its title, its field, its format.
struct Column {
  const char* title;
  double perception::BandStatistics::*field;
  const char* format;
  const char* json_key;
};

constexpr Column kColumns[] = {
    {"FAST corners", &perception::BandStatistics::fast_corners, "%10.1f", "fast_corners"},
    {"Shi-Tomasi corners", &perception::BandStatistics::shi_tomasi_corners, "%10.1f",
     "shi_tomasi_corners"},
    {"mean gradient", &perception::BandStatistics::mean_gradient, "%10.2f", "mean_gradient"},
    {"spectrum slope", &perception::BandStatistics::spectrum_slope, "%10.3f", "spectrum_slope"},
    {"grey mean", &perception::BandStatistics::grey_mean, "%10.1f", "grey_mean"},
    {"grey std", &perception::BandStatistics::grey_std, "%10.1f", "grey_std"},
    {"track share", &perception::BandStatistics::track_share, "%10.3f", "track_share"},
};

std::string FormatCell(const char* format, double value) {
  if (!std::isfinite(value)) return "       n/a";
  char buf[32];
  std::snprintf(buf, sizeof(buf), format, value);
  return buf;
}

void PrintTables(const std::vector<Measured>& measured, int bands) {
  std::size_t width = 24;
  for (const Measured& m : measured) width = std::max(width, m.folder.size() + 2);
  std::printf("%-*s %6s %11s %s\n", static_cast<int>(width), "folder", "images", "size",
              "first .. last image");
  for (const Measured& m : measured) {
    const perception::FolderStatistics& s = m.statistics;
    std::printf("%-*s %6zu %5d x %-4d %s .. %s\n", static_cast<int>(width), m.folder.c_str(),
                s.images.size(), s.image_size.width, s.image_size.height,
                s.images.front().filename().string().c_str(),
                s.images.back().filename().string().c_str());
  }
  for (const Column& c : kColumns) {
    std::printf("\n%-*s", static_cast<int>(width), c.title);
    for (int b = 1; b <= bands; ++b) std::printf("    band %d", b);
    std::printf("\n");
    for (const Measured& m : measured) {
      std::printf("%-*s", static_cast<int>(width), m.folder.c_str());
      for (const perception::BandStatistics& band : m.statistics.bands) {
        std::printf("%s", FormatCell(c.format, band.*(c.field)).c_str());
      }
      std::printf("\n");
    }
  }
}

nlohmann::json ToJson(const Measured& m) {
  const perception::FolderStatistics& s = m.statistics;
  nlohmann::json folder;
  folder["folder"] = m.folder;
  folder["path"] = fs::absolute(m.folder).lexically_normal().string();
  nlohmann::json images = nlohmann::json::array();
  for (const fs::path& p : s.images) images.push_back(p.filename().string());
  folder["images"] = images;
  folder["image_size"] = {s.image_size.width, s.image_size.height};
  nlohmann::json bands = nlohmann::json::array();
  for (const perception::BandStatistics& b : s.bands) {
    nlohmann::json band;
    band["rows"] = {b.row_begin, b.row_end};
    for (const Column& c : kColumns) {
      const double v = b.*(c.field);
      band[c.json_key] = std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
    }
    bands.push_back(band);
  }
  folder["bands"] = bands;
  return folder;
}

void WriteJson(const std::string& path, const ImageStatsArguments& args,
               const std::vector<Measured>& measured) {
  nlohmann::json j;
  j["options"] = nlohmann::json::parse(archive::ToJson(archive::Write(args.options)));
  j["selection"] = nlohmann::json::parse(archive::ToJson(archive::Write(args.selection)));
  j["folders"] = nlohmann::json::array();
  for (const Measured& m : measured) j["folders"].push_back(ToJson(m));
  std::ofstream out(path, std::ios::trunc);
  out << j.dump(2) << "\n";
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot be written");
}

// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return quoted + "\"";
}

void WriteCsv(const std::string& path, const std::vector<Measured>& measured) {
  std::ofstream out(path, std::ios::trunc);
  out << "folder,band,row_begin,row_end,images";
  for (const Column& c : kColumns) out << "," << c.json_key;
  out << "\n";
  for (const Measured& m : measured) {
    for (std::size_t b = 0; b < m.statistics.bands.size(); ++b) {
      const perception::BandStatistics& band = m.statistics.bands[b];
      out << CsvField(m.folder) << "," << b + 1 << "," << band.row_begin << "," << band.row_end
          << "," << m.statistics.images.size();
      for (const Column& c : kColumns) {
        const double v = band.*(c.field);
        char buf[32] = "";
        if (std::isfinite(v)) std::snprintf(buf, sizeof(buf), "%.9g", v);
        out << "," << buf;
      }
      out << "\n";
    }
  }
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot be written");
}

void RunImageStats(const ImageStatsArguments& args) {
  try {
    args.selection.Validate();
    args.options.Validate();
  } catch (const OptionError& e) {
    throw std::runtime_error("--" + e.field() + ": " + e.reason());
  }
  std::vector<Measured> measured;
  for (const std::string& folder : args.folders) {
    measured.push_back({folder, perception::MeasureFolder(folder, args.selection, args.options)});
  }
  PrintTables(measured, args.options.bands);
  if (!args.json_file.empty()) WriteJson(args.json_file, args, measured);
  if (!args.csv_file.empty()) WriteCsv(args.csv_file, measured);
}

}  // namespace

void AddImageStatsCommand(CLI::App& app) {
  auto args = std::make_shared<ImageStatsArguments>();
  CLI::App* cmd = app.add_subcommand(
      "image-stats",
      "Image statistics per band of rows over folders of images (run folders, KITTI "
      "sequences, PNG folders): FAST and Shi-Tomasi corners, mean gradient, spectrum slope, "
      "grey mean and spread, LK track share (docs/image_statistics.md)");
  cmd->add_option("folders", args->folders,
                  "Folders: a run folder (images/image_0/), a KITTI sequence (image_0/) or PNG "
                  "images")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--every", args->selection.every, "Measure every N-th image (default 5)");
  cmd->add_option("--first", args->selection.first,
                  "Index of the first image measured, in file-name order (default 0)");
  cmd->add_option("--count", args->selection.count,
                  "At most N images measured per folder (default 0: all)");
  cmd->add_option("--bands", args->options.bands,
                  "Horizontal bands of rows, top to bottom (default 4)");
  cmd->add_option("--json", args->json_file, "Write the figures as JSON to FILE");
  cmd->add_option("--csv", args->csv_file, "Write the figures as CSV to FILE (folder x band)");
  cmd->callback([args]() { RunCommand("image-stats", [&] { RunImageStats(*args); }); });
}

}  // namespace trackbed::apps
