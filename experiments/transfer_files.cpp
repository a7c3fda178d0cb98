// The transfer study's files (see transfer_files.h).
#include "trackbed/experiments/transfer_files.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "trackbed/common/archive.h"
#include "trackbed/experiments/rank_correlation.h"
#include "trackbed/plot/plots.h"

namespace trackbed::experiments {
namespace {

namespace fs = std::filesystem;

// One CSV line's fields: a field in double quotes may hold commas, and "" for a quote
// (summary.csv's reasons); spaces around unquoted fields are dropped.
std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  for (std::string& f : fields) {
    while (!f.empty() && f.back() == ' ') f.pop_back();
    while (!f.empty() && f.front() == ' ') f.erase(f.begin());
  }
  return fields;
}

// The columns a table is read by: a plain outcome table's, or a sweep's summary.csv's.
struct TableColumns {
  const char* config = "config";
  const char* sequence = "sequence";
  const char* frame = "frame";
  const char* status = nullptr;  // rows whose status is not "ok" are an error
};

std::optional<std::size_t> Column(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) return std::nullopt;
  return static_cast<std::size_t>(it - header.begin());
}

// The rows of one table added to `table`; `config_name` (non-empty) stands for a missing
// config column, `sequence_name` for a missing sequence column.
void ReadTable(const fs::path& csv, const std::string& metric, const std::string& config_name,
               const std::string& sequence_name, OutcomeTable* table,
               const TableColumns& columns = {}) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(csv.string() + ": cannot be read");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(csv.string() + ": empty (no header)");
  const std::vector<std::string> header = SplitCsvLine(line);
  const std::optional<std::size_t> config = Column(header, columns.config);
  const std::optional<std::size_t> sequence = Column(header, columns.sequence);
  const std::optional<std::size_t> frame = Column(header, columns.frame);
  constexpr std::size_t kAbsent = std::string::npos;
  const std::size_t status =
      columns.status ? Column(header, columns.status).value_or(kAbsent) : kAbsent;
  const std::optional<std::size_t> value = Column(header, metric);
  const auto fail = [&csv](int line_no, const std::string& reason) {
    return std::runtime_error(csv.string() + ":" + std::to_string(line_no) + ": " + reason);
  };
  if (!config && config_name.empty()) {
    throw fail(1, "no '" + std::string(columns.config) + "' column");
  }
  if (!value) throw fail(1, "no '" + metric + "' column (the metric)");
  std::map<std::pair<std::string, std::string>, std::size_t> index;  // → the sequence's
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> f = SplitCsvLine(line);
    if (f.size() != header.size()) {
      throw fail(line_no, std::to_string(f.size()) + " fields, the header has " +
                              std::to_string(header.size()));
    }
    const std::string name = config ? f[*config] : config_name;
    if (name.empty()) throw fail(line_no, "empty " + std::string(columns.config));
    if (status != kAbsent && f[status] != "ok") {
      throw fail(line_no, "a cell of '" + name + "' did not finish (" + f[status] +
                              "): resume the sweep, or leave its configuration out");
    }
    const std::string seq = sequence ? f[*sequence] : sequence_name;
    const std::optional<double> x = archive::ParseDouble(f[*value]);
    if (!x || !std::isfinite(*x)) {
      throw fail(line_no, metric + ": expected a finite number, got '" + f[*value] + "'");
    }
    std::vector<SequenceOutcome>& list = (*table)[name];
    const auto [it, added] = index.emplace(std::make_pair(name, seq), list.size());
    if (added) {
      for (const SequenceOutcome& other : list) {
        if (other.sequence == seq) {
          throw fail(line_no, "sequence '" + seq + "' of '" + name + "' is in another table too");
        }
      }
      list.push_back({seq, {}, {}});
    }
    SequenceOutcome& s = list[it->second];
    if (frame) {
      const std::optional<long long> k = archive::ParseSigned(f[*frame]);
      if (!k || *k < 0) {
        throw fail(line_no, "frame: expected an index >= 0, got '" + f[*frame] + "'");
      }
      s.frames.push_back(static_cast<long>(*k));
    }
    s.values.push_back(*x);
  }
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot be read");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A `trackbed vo` output's options (compact JSON), or nothing without vo_metrics.json.
std::optional<std::string> VoOptions(const fs::path& dir) {
  const fs::path json = dir / "vo_metrics.json";
  if (!fs::exists(json)) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(ReadText(json));
    if (!j.contains("options")) return std::nullopt;
    return j.at("options").dump();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(json.string() + ": " + e.what());
  }
}

OutcomeInput ReadFolder(const fs::path& dir, const std::string& metric) {
  OutcomeInput input;
  std::vector<fs::path> configs;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    if (e.is_directory()) configs.push_back(e.path());
  }
  std::sort(configs.begin(), configs.end());
  if (configs.empty()) throw std::runtime_error(dir.string() + ": no configuration folders");
  for (const fs::path& config : configs) {
    const std::string name = config.filename().string();
    std::vector<fs::path> outputs;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(config)) {
      if (e.path().filename() == "vo_frame_errors.csv") outputs.push_back(e.path().parent_path());
    }
    std::sort(outputs.begin(), outputs.end());
    if (outputs.empty()) {
      throw std::runtime_error(config.string() +
                               ": no vo_frame_errors.csv (a `trackbed vo` output with ground "
                               "truth) in it or below");
    }
    for (const fs::path& out : outputs) {
      const std::string sequence = out.lexically_relative(config).string();
      ReadTable(out / "vo_frame_errors.csv", metric, name, sequence, &input.table);
      const std::optional<std::string> options = VoOptions(out);
      if (!options) continue;
      const auto [it, added] = input.settings.emplace(name, *options);
      if (!added && it->second != *options) {
        throw std::runtime_error(out.string() + ": the VO's options differ from those of " +
                                 outputs.front().string() + " (one configuration, one setting)");
      }
    }
  }
  return input;
}

// The first key whose values differ, with both values, dotted.
std::optional<std::string> FirstDifference(const nlohmann::json& a, const nlohmann::json& b,
                                           const std::string& path) {
  if (a.is_object() && b.is_object()) {
    for (const auto& [key, value] : a.items()) {
      const std::string p = path.empty() ? key : path + "." + key;
      if (!b.contains(key)) return p + " (only on the real side)";
      if (auto d = FirstDifference(value, b.at(key), p)) return d;
    }
    for (const auto& [key, value] : b.items()) {
      if (!a.contains(key)) return (path.empty() ? key : path + "." + key) + " (only simulated)";
    }
    return std::nullopt;
  }
  if (a == b) return std::nullopt;
  return path + " (" + a.dump() + " real, " + b.dump() + " simulated)";
}

std::string FormatInterval(const Interval& in) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "[%.3f, %.3f]", in.low, in.high);
  return buf;
}

nlohmann::json IntervalJson(const Interval& in) {
  const auto num = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
  return {{"low", num(in.low)}, {"high", num(in.high)}, {"resamples", in.resamples}};
}

nlohmann::json MeasureJson(const Measure& m) {
  return {{"value", std::isfinite(m.value) ? nlohmann::json(m.value) : nlohmann::json()},
          {"interval", IntervalJson(m.both)},
          {"interval_frames", IntervalJson(m.frames)},
          {"interval_configurations", IntervalJson(m.configurations)}};
}

nlohmann::json AgreementJson(const Agreement& a) {
  return {{"configurations", a.configurations},
          {"spearman_rho", MeasureJson(a.spearman)},
          {"pearson_r", MeasureJson(a.pearson)},
          {"mmrv", MeasureJson(a.mmrv)}};
}

nlohmann::json SplitHalfJson(const SplitHalf& h) {
  const auto num = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
  return {{"available", h.available},
          {"spearman_rho", num(h.spearman)},
          {"pearson_r", num(h.pearson)},
          {"spearman_rho_full_length", num(h.spearman_full)},
          {"pearson_r_full_length", num(h.pearson_full)}};
}

std::string AgreementLines(const Agreement& a, const char* indent) {
  std::ostringstream s;
  const auto line = [&s, indent](const char* name, const Measure& m) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "%s%-13s %7.3f  ", indent, name, m.value);
    s << buf << FormatInterval(m.both) << " (frames " << FormatInterval(m.frames)
      << ", configurations " << FormatInterval(m.configurations) << ")\n";
  };
  line("Spearman rho", a.spearman);
  line("Pearson r", a.pearson);
  line("MMRV", a.mmrv);
  return s.str();
}

// Ranks with 1 the best.
std::vector<double> BestFirstRanks(std::vector<double> x, bool higher_is_better) {
  if (higher_is_better) {
    for (double& v : x) v = -v;
  }
  return AverageRanks(x);
}

// outcomes.csv, transfer.png (ranks) and transfer_values.png (outcomes).
void WriteOutcomesAndPlots(const fs::path& out_dir, const TransferFigures& f,
                           const std::string& metric) {
  const std::vector<double> real_rank = BestFirstRanks(f.real, f.options.higher_is_better);
  const std::vector<double> sim_rank = BestFirstRanks(f.sim, f.options.higher_is_better);
  const fs::path csv_path = out_dir / "outcomes.csv";
  std::ofstream csv(csv_path, std::ios::trunc);
  csv << "config,real,sim,real_rank,sim_rank,near_best\n";
  std::vector<plot::ScatterPoint> ranks, values;
  for (std::size_t i = 0; i < f.configurations.size(); ++i) {
    const std::string& name = f.configurations[i];
    const bool near =
        std::find(f.near_best.configurations.begin(), f.near_best.configurations.end(), name) !=
        f.near_best.configurations.end();
    csv << name << "," << archive::FormatDouble(f.real[i]) << "," << archive::FormatDouble(f.sim[i])
        << "," << archive::FormatDouble(real_rank[i]) << "," << archive::FormatDouble(sim_rank[i])
        << "," << (near ? 1 : 0) << "\n";
    ranks.push_back({{real_rank[i], sim_rank[i]}, name, near ? 0u : 1u});
    values.push_back({{f.real[i], f.sim[i]}, name, near ? 0u : 1u});
  }
  csv.close();
  if (!csv) throw std::runtime_error(csv_path.string() + ": write failed");
  char title[160];
  std::snprintf(title, sizeof(title), "%s, ranks (1 = best): rho %.2f, r %.2f, MMRV %.3f",
                metric.c_str(), f.all.spearman.value, f.all.pearson.value, f.all.mmrv.value);
  char near_name[96];
  std::snprintf(near_name, sizeof(near_name), "within %gx of the best on real",
                f.options.near_best_factor);
  plot::WriteScatterPlot(out_dir / "transfer.png", title, "rank on real data", "rank in simulation",
                         ranks, {near_name, "the others"}, true);
  plot::WriteScatterPlot(out_dir / "transfer_values.png",
                         metric + ": each configuration's median, simulated against real",
                         "real " + metric, "simulated " + metric, values,
                         {near_name, "the others"});
}

}  // namespace

OutcomeInput ReadOutcomes(const fs::path& path, const std::string& metric) {
  if (fs::is_directory(path) && fs::exists(path / "summary.csv") &&
      fs::exists(path / "cells.json")) {
    // A sweep folder: a configuration is a group (a cell without its seed), a sequence
    // a seed, one value per cell.
    OutcomeInput input;
    TableColumns sweep;
    sweep.config = "group";
    sweep.sequence = "seed";
    sweep.status = "cell_status";
    ReadTable(path / "summary.csv", metric, "", "", &input.table, sweep);
    return input;
  }
  if (fs::is_directory(path)) return ReadFolder(path, metric);
  if (!fs::exists(path)) throw std::runtime_error(path.string() + ": no such file or folder");
  OutcomeInput input;
  ReadTable(path, metric, "", "", &input.table);
  if (input.table.empty()) throw std::runtime_error(path.string() + ": no rows");
  return input;
}

void CheckSameSettings(const OutcomeInput& real, const OutcomeInput& sim) {
  for (const auto& [name, options] : real.settings) {
    const auto it = sim.settings.find(name);
    if (it == sim.settings.end()) continue;
    const std::optional<std::string> d =
        FirstDifference(nlohmann::json::parse(options), nlohmann::json::parse(it->second), "");
    if (d) {
      throw std::runtime_error("configuration '" + name +
                               "': the real and simulated runs had different VO options: " + *d);
    }
  }
}

void WriteOutcomeTable(const fs::path& csv, const OutcomeTable& table, const std::string& metric) {
  std::ofstream out(csv, std::ios::trunc);
  out << "config,sequence,frame," << metric << "\n";
  for (const auto& [name, sequences] : table) {
    for (const SequenceOutcome& s : sequences) {
      for (std::size_t k = 0; k < s.values.size(); ++k) {
        out << name << "," << s.sequence << ","
            << (s.frames.empty() ? std::string() : std::to_string(s.frames[k])) << ","
            << archive::FormatDouble(s.values[k]) << "\n";
      }
    }
  }
  out.close();
  if (!out) throw std::runtime_error(csv.string() + ": write failed");
}

void WriteTransferFiles(const fs::path& out_dir, const TransferFigures& f,
                        const std::string& metric) {
  fs::create_directories(out_dir);
  const TransferOptions& o = f.options;
  nlohmann::json j;
  j["metric"] = metric;
  j["better"] = o.higher_is_better ? "higher" : "lower";
  j["bootstrap"] = {{"resamples", o.resamples},
                    {"seed", o.seed},
                    {"block_frames", o.block_frames},
                    {"level", o.level}};
  j["near_best_factor"] = o.near_best_factor;
  nlohmann::json outcomes = nlohmann::json::array();
  for (std::size_t i = 0; i < f.configurations.size(); ++i) {
    outcomes.push_back({{"config", f.configurations[i]}, {"real", f.real[i]}, {"sim", f.sim[i]}});
  }
  j["outcomes"] = outcomes;
  j["all"] = AgreementJson(f.all);
  j["near_best"] = AgreementJson(f.near_best);
  j["ceiling"] = {{"real_split_half", SplitHalfJson(f.real_ceiling)},
                  {"sim_split_half", SplitHalfJson(f.sim_ceiling)}};
  const fs::path json_path = out_dir / "transfer.json";
  std::ofstream json(json_path, std::ios::trunc);
  json << j.dump(2) << "\n";
  json.close();
  if (!json) throw std::runtime_error(json_path.string() + ": write failed");

  WriteOutcomesAndPlots(out_dir, f, metric);
}

std::string FormatTransferFigures(const TransferFigures& f, const std::string& metric) {
  std::ostringstream s;
  const TransferOptions& o = f.options;
  s << "configurations: " << f.configurations.size() << "; metric " << metric
    << " (each configuration's median; " << (o.higher_is_better ? "higher" : "lower")
    << " is better)\n";
  s << "intervals: " << 100.0 * o.level << " % percentile bootstrap, " << o.resamples
    << " resamples (seed " << o.seed << "), frames in blocks of " << o.block_frames
    << " paired across configurations; [frames and configurations resampled] (frames "
       "only, configurations only)\n";
  s << "all configurations:\n" << AgreementLines(f.all, "  ");
  const auto ceiling = [&s](const char* side, const SplitHalf& h, int block) {
    if (!h.available) {
      s << "ceiling, " << side << ": no frame indices, no split-half\n";
      return;
    }
    char buf[200];
    std::snprintf(buf, sizeof(buf),
                  "ceiling, %s split-half (alternating %d-frame blocks): rho %.3f (full length "
                  "%.3f), r %.3f (full length %.3f)\n",
                  side, block, h.spearman, h.spearman_full, h.pearson, h.pearson_full);
    s << buf;
  };
  ceiling("real", f.real_ceiling, o.block_frames);
  ceiling("simulated", f.sim_ceiling, o.block_frames);
  s << "near the best (real within " << o.near_best_factor
    << "x of the best: " << f.near_best.configurations.size() << " configurations):\n"
    << AgreementLines(f.near_best, "  ");
  return s.str();
}

}  // namespace trackbed::experiments
