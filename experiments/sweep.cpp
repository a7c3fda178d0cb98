// Sweep cells: expansion and naming, the sweep folder's layout, and its JSON files
// (cells.json, cells/NAME/cell.json) through the config archive (see sweep.h and
// docs/sweeps.md). Sweep files themselves are read and written in sweep_file.cpp.
#include "trackbed/experiments/sweep.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>
#include <utility>

#include "trackbed/common/archive.h"

namespace trackbed::experiments {

namespace fs = std::filesystem;
using archive::Node;

SweepError::SweepError(std::string source, std::string key, std::string reason)
    : std::runtime_error(source + ": " + (key.empty() ? "" : key + ": ") + reason),
      source_(std::move(source)),
      key_(std::move(key)),
      reason_(std::move(reason)) {}

namespace {

// Longest cell name: well under NAME_MAX (255) with room for temporary suffixes.
constexpr std::size_t kMaxCellNameLength = 200;
// Longest value token in a cell name before it is shortened and hashed.
constexpr std::size_t kMaxValueTokenLength = 32;

// 32-bit FNV-1a: a short, stable tag for values whose text cannot be a file name.
std::string Hash8(const std::string& text) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : text) {
    h ^= c;
    h *= 16777619u;
  }
  char buf[16];
  std::snprintf(buf, sizeof(buf), "%08x", h);
  return buf;
}

// [A-Za-z0-9._+-] kept, anything else (and runs of it) one '_', ends trimmed.
std::string Sanitize(const std::string& raw) {
  std::string s;
  for (char c : raw) {
    const bool keep =
        std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' || c == '_';
    const char out = keep ? c : '_';
    if (out == '_' && !s.empty() && s.back() == '_') continue;
    s.push_back(out);
  }
  while (!s.empty() && s.front() == '_') s.erase(s.begin());
  while (!s.empty() && s.back() == '_') s.pop_back();
  return s;
}

// A name ExpandSweep could have made: a single safe folder name under cells/.
bool IsCellName(const std::string& name) {
  const bool safe = std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+' ||
           c == '_';
  });
  return safe && !name.empty() && name.size() <= kMaxCellNameLength && name != "." && name != "..";
}

// A value as part of a cell name: itself when it is safe and short, else its
// sanitized (and shortened) text and a hash of the original.
std::string ValueToken(const std::string& raw) {
  const std::string s = Sanitize(raw);
  if (s == raw && !s.empty() && s.size() <= kMaxValueTokenLength) return s;
  return s.substr(0, kMaxValueTokenLength) + (s.empty() ? "" : "-") + Hash8(raw);
}

// The label of each scenario in cell names: its file stem, or its whole path as
// written when stems clash.
std::vector<std::string> ScenarioLabels(const SweepSpec& spec) {
  std::vector<std::string> stems;
  for (const std::string& s : spec.scenarios) stems.push_back(ValueToken(fs::path(s).stem()));
  std::vector<std::string> labels = stems;
  for (std::size_t i = 0; i < stems.size(); ++i) {
    if (std::count(stems.begin(), stems.end(), stems[i]) < 2) continue;
    std::string joined;
    for (const fs::path& part :
         fs::path(spec.scenarios[i]).parent_path() / fs::path(spec.scenarios[i]).stem()) {
      const std::string p = part.string();
      if (p == "." || p == "/" || p.empty()) continue;
      joined += (joined.empty() ? "" : "-") + (p == ".." ? std::string("up") : p);
    }
    labels[i] = ValueToken(joined);
  }
  return labels;
}

// The label of each axis in cell names: the last part of its key, or the whole key
// when two axes share the last part.
std::vector<std::string> AxisLabels(const SweepSpec& spec) {
  std::vector<std::string> last;
  for (const SweepAxis& a : spec.vary) {
    const std::size_t dot = a.key.find_last_of('.');
    last.push_back(Sanitize(dot == std::string::npos ? a.key : a.key.substr(dot + 1)));
  }
  std::vector<std::string> labels = last;
  for (std::size_t i = 0; i < last.size(); ++i) {
    if (std::count(last.begin(), last.end(), last[i]) > 1) labels[i] = Sanitize(spec.vary[i].key);
  }
  return labels;
}

// ---------------------------------------------------------------------------
// The sweep folder's JSON files, read in the archive's brief wording like sweep files.

constexpr archive::Wording kFolderWording = archive::Wording::kBrief;

/// A cell in cells.json: `vary` maps each varied key to its value, `set` lists the
/// whole `--set` list as `key=value` texts.
struct CellFields {
  std::uint64_t index = 0;
  std::string name, group, scenario, scenario_path;
  std::uint64_t seed = 0;
  archive::Entries<std::string> vary;
  std::vector<std::string> set;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("index", &index, archive::kRequired);
    a->Visit("name", &name, archive::kRequired);
    a->Visit("group", &group, archive::kRequired);
    a->Visit("scenario", &scenario, archive::kRequired);
    a->Visit("scenario_path", &scenario_path, archive::kRequired);
    a->Visit("seed", &seed, archive::kRequired);
    a->Visit("vary", &vary, archive::kRequired);
    a->Visit("set", &set, archive::kRequired);
  }
};

/// cells.json.
struct PlanFields {
  std::string sweep;
  std::optional<double> timeout_s;  // null: no limit
  std::vector<std::string> vary_keys, replicate_keys;
  std::vector<CellFields> cells;
  std::vector<SweepExpectation> expect;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("sweep", &sweep, archive::kRequired);
    a->Visit("timeout_s", &timeout_s);
    a->Visit("vary_keys", &vary_keys, archive::kRequired);
    a->Visit("replicate_keys", &replicate_keys, archive::kRequired);
    a->Visit("cells", &cells, archive::kRequired);
    a->Visit("expect", &expect, archive::kOmitEmpty);
  }
};

/// cells/NAME/cell.json: which cell (written for people and tools reading the folder;
/// the cell list is cells.json's) and its outcome.
struct OutcomeFields {
  std::string cell;
  std::uint64_t index = 0;
  std::string scenario;
  std::uint64_t seed = 0;
  std::vector<std::string> set;
  CellOutcome outcome;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("cell", &cell);
    a->Visit("index", &index);
    a->Visit("scenario", &scenario);
    a->Visit("seed", &seed);
    a->Visit("set", &set);
    a->VisitEnum("status", &outcome.status,
                 {{ToString(CellStatus::kPending), CellStatus::kPending},
                  {ToString(CellStatus::kOk), CellStatus::kOk},
                  {ToString(CellStatus::kFailed), CellStatus::kFailed},
                  {ToString(CellStatus::kTimedOut), CellStatus::kTimedOut},
                  {ToString(CellStatus::kInterrupted), CellStatus::kInterrupted}},
                 archive::kRequired);
    a->Visit("exit_code", &outcome.exit_code);  // null: the run did not exit
    a->Visit("reason", &outcome.reason, archive::kRequired);
    a->Visit("stderr_tail", &outcome.stderr_tail, archive::kRequired);
    a->Visit("wall_time_s", &outcome.wall_time_s, archive::kRequired);
    a->Visit("host", &outcome.host, archive::kRequired);
    a->Visit("started_utc", &outcome.started_utc, archive::kRequired);
    a->Visit("slurm_job", &outcome.slurm_job, archive::kOmitEmpty);  // only under Slurm
  }
};

// Reads a JSON file of the sweep folder into `fields`; errors name `source`.
template <class Fields>
void ReadJson(const std::string& json_text, const std::string& source, Fields* fields) {
  try {
    archive::Read(archive::ParseJson(json_text), "", kFolderWording, fields);
  } catch (const archive::Error& e) {
    throw SweepError(source, e.path(), e.reason());
  }
}

std::vector<std::string> OverrideTexts(const std::vector<scenario::Override>& overrides) {
  std::vector<std::string> texts;
  for (const scenario::Override& o : overrides) texts.push_back(scenario::OverrideText(o));
  return texts;
}

}  // namespace

std::vector<SweepCell> ExpandSweep(const SweepSpec& spec) {
  const std::vector<std::string> scenario_labels = ScenarioLabels(spec);
  const std::vector<std::string> axis_labels = AxisLabels(spec);
  std::size_t combinations = 1;
  for (const SweepAxis& a : spec.vary) combinations *= a.values.size();
  std::vector<SweepCell> cells;
  std::map<std::string, std::size_t> index_of_name;
  for (std::size_t s = 0; s < spec.scenarios.size(); ++s) {
    const fs::path p = fs::path(spec.scenarios[s]).is_absolute()
                           ? fs::path(spec.scenarios[s])
                           : spec.base_dir / spec.scenarios[s];
    for (std::size_t c = 0; c < combinations; ++c) {
      // Mixed-radix digits of c, the last axis fastest.
      std::vector<std::size_t> digit(spec.vary.size());
      std::size_t rest = c;
      for (std::size_t a = spec.vary.size(); a-- > 0;) {
        digit[a] = rest % spec.vary[a].values.size();
        rest /= spec.vary[a].values.size();
      }
      std::string group = scenario_labels[s], name = scenario_labels[s];
      std::vector<scenario::Override> varied;
      for (std::size_t a = 0; a < spec.vary.size(); ++a) {
        const std::string& value = spec.vary[a].values[digit[a]];
        varied.push_back({spec.vary[a].key, value});
        const std::string part = "__" + axis_labels[a] + "-" + ValueToken(value);
        name += part;
        if (!spec.vary[a].replicate) group += part;
      }
      for (std::uint64_t seed : spec.seeds) {
        SweepCell cell;
        cell.index = cells.size();
        cell.group = group;
        cell.name = name + "__seed-" + std::to_string(seed);
        cell.scenario = spec.scenarios[s];
        cell.scenario_path = p.lexically_normal();
        cell.seed = seed;
        cell.varied = varied;
        cell.overrides = spec.set;
        cell.overrides.insert(cell.overrides.end(), varied.begin(), varied.end());
        if (cell.name.size() > kMaxCellNameLength) {
          throw SweepError(spec.source, "vary",
                           "cell name longer than " + std::to_string(kMaxCellNameLength) +
                               " characters: " + cell.name);
        }
        const auto [it, fresh] = index_of_name.emplace(cell.name, cell.index);
        if (!fresh) {
          throw SweepError(spec.source, "",
                           "cells " + std::to_string(it->second) + " and " +
                               std::to_string(cell.index) + " would share the folder name " +
                               cell.name);
        }
        cells.push_back(std::move(cell));
      }
    }
  }
  return cells;
}

std::vector<std::string> SweepPlan::GroupKeys() const {
  std::vector<std::string> keys;
  for (const std::string& k : vary_keys) {
    if (std::find(replicate_keys.begin(), replicate_keys.end(), k) == replicate_keys.end()) {
      keys.push_back(k);
    }
  }
  return keys;
}

SweepPlan MakeSweepPlan(const SweepSpec& spec) {
  SweepPlan plan;
  plan.name = spec.name;
  plan.timeout_s = spec.timeout_s;
  for (const SweepAxis& a : spec.vary) {
    plan.vary_keys.push_back(a.key);
    if (a.replicate) plan.replicate_keys.push_back(a.key);
  }
  plan.cells = ExpandSweep(spec);
  plan.expect = spec.expect;
  return plan;
}

std::string SweepPlanJson(const SweepPlan& plan) {
  PlanFields fields;
  fields.sweep = plan.name;
  fields.timeout_s = plan.timeout_s;
  fields.vary_keys = plan.vary_keys;
  fields.replicate_keys = plan.replicate_keys;
  fields.expect = plan.expect;
  for (const SweepCell& c : plan.cells) {
    CellFields& cell = fields.cells.emplace_back();
    cell.index = c.index;
    cell.name = c.name;
    cell.group = c.group;
    cell.scenario = c.scenario;
    cell.scenario_path = c.scenario_path.string();
    cell.seed = c.seed;
    for (const scenario::Override& o : c.varied) cell.vary.emplace_back(o.key, o.value);
    cell.set = OverrideTexts(c.overrides);
  }
  return archive::ToJson(archive::Write(fields)) + "\n";
}

SweepPlan ParseSweepPlan(const std::string& json_text, const std::string& source_name) {
  PlanFields fields;
  ReadJson(json_text, source_name, &fields);
  SweepPlan plan;
  plan.name = fields.sweep;
  plan.timeout_s = fields.timeout_s;
  plan.vary_keys = fields.vary_keys;
  plan.replicate_keys = fields.replicate_keys;
  plan.expect = fields.expect;
  for (std::size_t i = 0; i < fields.expect.size(); ++i) {
    const std::string problem = fields.expect[i].Problem();
    if (!problem.empty()) {
      throw SweepError(source_name, archive::JoinIndex("expect", i), problem);
    }
  }
  std::map<std::string, std::size_t> index_of_name;
  for (std::size_t i = 0; i < fields.cells.size(); ++i) {
    const CellFields& c = fields.cells[i];
    const std::string where = archive::JoinIndex("cells", i);
    if (c.index != i) throw SweepError(source_name, where + ".index", "out of order");
    // The name is the cell's folder under cells/: only what ExpandSweep makes, and once.
    if (!IsCellName(c.name)) {
      throw SweepError(source_name, where + ".name",
                       "not a cell name (1 to " + std::to_string(kMaxCellNameLength) +
                           " of [A-Za-z0-9._+-], not . or ..): '" + c.name + "'");
    }
    if (const auto [it, fresh] = index_of_name.emplace(c.name, i); !fresh) {
      throw SweepError(
          source_name, where + ".name",
          "'" + c.name + "' is also the name of cells[" + std::to_string(it->second) + "]");
    }
    SweepCell cell;
    cell.index = i;
    cell.name = c.name;
    cell.group = c.group;
    cell.scenario = c.scenario;
    cell.scenario_path = c.scenario_path;
    cell.seed = c.seed;
    for (const auto& [key, value] : c.vary) cell.varied.push_back({key, value});
    for (const std::string& s : c.set) {
      try {
        cell.overrides.push_back(scenario::ParseOverride(s));
      } catch (const std::invalid_argument& e) {
        throw SweepError(source_name, where + ".set", e.what());
      }
    }
    plan.cells.push_back(std::move(cell));
  }
  return plan;
}

SweepPlan ReadSweepPlan(const fs::path& sweep_dir) {
  const fs::path path = sweep_dir / "cells.json";
  if (!fs::exists(path)) {
    throw SweepError(sweep_dir.string(), "",
                     "not a sweep folder (no cells.json; `trackbed sweep` writes it)");
  }
  return ParseSweepPlan(ReadTextFile(path), path.string());
}

std::string PlanConflict(const SweepPlan& before, const SweepPlan& after) {
  std::map<std::string, const SweepCell*> old;
  for (const SweepCell& c : before.cells) old[c.name] = &c;
  const auto describe = [](const SweepCell& c) {
    std::string s = c.scenario + " --seed " + std::to_string(c.seed);
    for (const scenario::Override& o : c.overrides) s += " --set " + scenario::OverrideText(o);
    return s;
  };
  for (const SweepCell& c : after.cells) {
    const auto it = old.find(c.name);
    if (it == old.end()) continue;
    const SweepCell& o = *it->second;
    bool same =
        o.scenario == c.scenario && o.seed == c.seed && o.overrides.size() == c.overrides.size();
    for (std::size_t k = 0; same && k < c.overrides.size(); ++k) {
      same =
          o.overrides[k].key == c.overrides[k].key && o.overrides[k].value == c.overrides[k].value;
    }
    if (!same) {
      return "cell " + c.name + " was `" + describe(o) + "`, is now `" + describe(c) + "`";
    }
  }
  return "";
}

fs::path CellDir(const fs::path& sweep_dir, const SweepCell& cell) {
  return sweep_dir / "cells" / cell.name;
}
fs::path CellRunDir(const fs::path& sweep_dir, const SweepCell& cell) {
  return CellDir(sweep_dir, cell) / "run";
}
fs::path CellJsonPath(const fs::path& sweep_dir, const SweepCell& cell) {
  return CellDir(sweep_dir, cell) / "cell.json";
}
fs::path CellMetricsPath(const fs::path& sweep_dir, const SweepCell& cell) {
  return CellRunDir(sweep_dir, cell) / "metrics.json";
}

bool CellFinished(const fs::path& sweep_dir, const SweepCell& cell) {
  const fs::path metrics = CellMetricsPath(sweep_dir, cell);
  if (!fs::is_regular_file(metrics)) return false;
  // A file cut short (a crash of the machine before the data reached the disk) is
  // not a finished run.
  try {
    return archive::ParseJson(ReadTextFile(metrics)).Find("status") != nullptr;
  } catch (const std::exception&) {
    return false;
  }
}

std::optional<std::string> ValidateCell(const SweepCell& cell) {
  std::vector<scenario::Override> overrides = cell.overrides;
  overrides.push_back({"seed", std::to_string(cell.seed)});
  try {
    scenario::LoadScenario(cell.scenario_path.string(), overrides);
  } catch (const scenario::ScenarioError& e) {
    // The scenario as the sweep file names it, so the reason reads the same anywhere.
    const std::string source =
        e.source() == cell.scenario_path.string() ? cell.scenario : e.source();
    return source + ": " + (e.key().empty() ? "" : e.key() + ": ") + e.reason();
  } catch (const std::exception& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

const char* ToString(CellStatus status) {
  switch (status) {
    case CellStatus::kPending:
      return "pending";
    case CellStatus::kOk:
      return "ok";
    case CellStatus::kFailed:
      return "failed";
    case CellStatus::kTimedOut:
      return "timed_out";
    case CellStatus::kInterrupted:
      return "interrupted";
  }
  return "?";
}

std::string CellOutcomeJson(const SweepCell& cell, const CellOutcome& outcome) {
  OutcomeFields fields;
  fields.cell = cell.name;
  fields.index = cell.index;
  fields.scenario = cell.scenario;
  fields.seed = cell.seed;
  fields.set = OverrideTexts(cell.overrides);
  fields.outcome = outcome;
  return archive::ToJson(archive::Write(fields)) + "\n";
}

CellOutcome ParseCellOutcome(const std::string& json_text, const std::string& source_name) {
  OutcomeFields fields;
  ReadJson(json_text, source_name, &fields);
  return fields.outcome;
}

CellOutcome ReadCellOutcome(const fs::path& sweep_dir, const SweepCell& cell) {
  const fs::path path = CellJsonPath(sweep_dir, cell);
  if (!fs::exists(path)) return {};
  return ParseCellOutcome(ReadTextFile(path), path.string());
}

// metrics.json is a run's output, not an options file: only its status and stop reason
// are read, from the parsed tree.
CellOutcome OutcomeFromMetrics(const std::string& metrics_json_text) {
  CellOutcome o;
  o.status = CellStatus::kFailed;
  const auto text_of = [](const Node* n) -> std::optional<std::string> {
    if (n && n->IsScalar() && n->tag() == Node::Tag::kString) return n->text();
    return std::nullopt;
  };
  try {
    const Node metrics = archive::ParseJson(metrics_json_text);
    const std::optional<std::string> status = text_of(metrics.Find("status"));
    if (!status) {
      o.reason = "unreadable metrics.json: no status";
    } else if (*status == "completed") {
      o.status = CellStatus::kOk;
    } else {
      o.reason = "run failed: " + text_of(metrics.Find("stop_reason")).value_or(*status);
    }
  } catch (const archive::Error& e) {
    o.reason = std::string("unreadable metrics.json: ") + e.what();
  }
  return o;
}

std::string ReadTextFile(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error(path.string() + ": cannot read");
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace trackbed::experiments
