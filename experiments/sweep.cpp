// Sweep files, cell expansion and naming, and the sweep folder's JSON files (see
// sweep.h and docs/sweeps.md).
//
// The sweep reader is strict in the manner of the scenario reader: every key is
// known, every list is non-empty and free of duplicates, and an error names the
// file, the dotted key (`vary[1].range.step`) and the reason. Scalars are parsed
// with std::from_chars, not yaml-cpp's stream conversions, so that `-1` is not a
// seed and `1.5` is not an integer.
#include "trackbed/experiments/sweep.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <system_error>
#include <utility>

#include <yaml-cpp/yaml.h>
#include <nlohmann/json.hpp>

namespace trackbed::experiments {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

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
// Most values a range or a seed range may expand to.
constexpr std::size_t kMaxRangeValues = 10000;

std::string Indexed(const std::string& path, std::size_t k) {
  return path + "[" + std::to_string(k) + "]";
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

const char* Kind(const YAML::Node& n) {
  if (n.IsMap()) return "a map";
  if (n.IsSequence()) return "a list";
  if (n.IsNull()) return "null";
  return "a scalar";
}

// Reads one YAML node of a sweep file; errors carry the file and the dotted key.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& key, const std::string& reason) const {
    throw SweepError(source_, key, reason);
  }

  // Rejects keys of map `node` that are not in `known`.
  void OnlyKeys(const YAML::Node& node, const std::string& path,
                const std::vector<std::string>& known) const {
    for (const auto& entry : node) {
      const std::string key = entry.first.Scalar();
      if (std::find(known.begin(), known.end(), key) == known.end()) {
        Fail(path.empty() ? key : path + "." + key,
             "unknown key (expected one of: " + JoinNames(known) + ")");
      }
    }
  }

  YAML::Node Map(const YAML::Node& node, const std::string& key) const {
    if (!node.IsMap()) Fail(key, std::string("expected a map, got ") + Kind(node));
    return node;
  }

  YAML::Node List(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence()) Fail(key, std::string("expected a list, got ") + Kind(node));
    if (node.size() == 0) Fail(key, "must not be empty");
    return node;
  }

  std::string String(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) Fail(key, std::string("expected a string, got ") + Kind(node));
    if (node.Scalar().empty()) Fail(key, "must not be empty");
    return node.Scalar();
  }

  double Number(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) Fail(key, std::string("expected a number, got ") + Kind(node));
    const std::string& s = node.Scalar();
    double x = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(x)) {
      Fail(key, "expected a number, got '" + s + "'");
    }
    return x;
  }

  std::uint64_t Unsigned(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) {
      Fail(key, std::string("expected a non-negative integer, got ") + Kind(node));
    }
    const std::string& s = node.Scalar();
    std::uint64_t x = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), x);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size()) {
      Fail(key, "expected a non-negative integer, got '" + s + "'");
    }
    return x;
  }

 private:
  std::string source_;
};

// Flow style all the way down, so that a list value becomes one `--set` token.
void MakeFlow(YAML::Node node) {
  if (node.IsSequence() || node.IsMap()) {
    node.SetStyle(YAML::EmitterStyle::Flow);
    for (auto entry : node) {
      if (node.IsMap()) {
        MakeFlow(entry.second);
      } else {
        MakeFlow(entry);
      }
    }
  }
}

// A value node as the text `--set key=` takes: scalars as written, lists and maps in
// flow style.
std::string ValueText(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  YAML::Node copy = YAML::Clone(node);
  MakeFlow(copy);
  YAML::Emitter out;
  out << copy;
  return out.c_str();
}

// `from + k * step` printed with 12 significant digits (so 0.1 + 2 * 0.1 is 0.3),
// or as an integer when from, to and step are all integers.
std::vector<std::string> RangeValues(const Reader& reader, const YAML::Node& node,
                                     const std::string& key) {
  reader.Map(node, key);
  reader.OnlyKeys(node, key, {"from", "to", "step"});
  for (const char* k : {"from", "to"}) {
    if (!node[k]) reader.Fail(key, std::string("missing `") + k + "`");
  }
  const double from = reader.Number(node["from"], key + ".from");
  const double to = reader.Number(node["to"], key + ".to");
  const double step = node["step"] ? reader.Number(node["step"], key + ".step") : 1.0;
  if (!(step > 0)) reader.Fail(key + ".step", "must be > 0");
  if (to < from) reader.Fail(key + ".to", "must be >= from");
  const double count = std::floor((to - from) / step * (1.0 + 1e-12) + 1e-9) + 1.0;
  if (count > static_cast<double>(kMaxRangeValues)) {
    reader.Fail(key, "more than " + std::to_string(kMaxRangeValues) + " values");
  }
  const auto is_integer = [](double x) { return std::floor(x) == x && std::abs(x) < 1e15; };
  const bool integers = is_integer(from) && is_integer(step);
  std::vector<std::string> values;
  for (std::size_t k = 0; k < static_cast<std::size_t>(count); ++k) {
    const double v = from + static_cast<double>(k) * step;
    char buf[64];
    if (integers) {
      std::snprintf(buf, sizeof(buf), "%lld", static_cast<long long>(v));
    } else {
      std::snprintf(buf, sizeof(buf), "%.12g", v);
    }
    values.push_back(buf);
  }
  return values;
}

// Checks `key=value` syntax of a key the way `--set` would, without a value.
void CheckKey(const Reader& reader, const std::string& key, const std::string& where) {
  try {
    scenario::ParseOverride(key + "=0");
  } catch (const std::invalid_argument&) {
    reader.Fail(where, "'" + key + "' is not a dotted scenario key");
  }
  if (key == "seed") reader.Fail(where, "the seed comes from `seeds`, not from an override");
}

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

std::string OverrideText(const scenario::Override& o) { return o.key + "=" + o.value; }

Json ParseJson(const std::string& text, const std::string& source) {
  try {
    return Json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw SweepError(source, "", std::string("not valid JSON: ") + e.what());
  }
}

// Typed access to a JSON document's members with SweepError on mismatch.
template <class T>
T Get(const Json& j, const char* key, const std::string& source, const std::string& where) {
  const std::string path = where.empty() ? key : where + "." + key;
  if (!j.is_object() || !j.contains(key)) throw SweepError(source, path, "missing");
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception& e) {
    throw SweepError(source, path, std::string("wrong type: ") + e.what());
  }
}

}  // namespace

SweepSpec ParseSweep(const std::string& yaml_text, const std::string& source_name,
                     const fs::path& file_dir) {
  const Reader reader(source_name);
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    reader.Fail("", "YAML syntax error at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  if (!root.IsMap()) {
    reader.Fail("", std::string("expected a map of sweep keys, got ") + Kind(root));
  }
  reader.OnlyKeys(root, "", {"name", "base_dir", "scenarios", "seeds", "set", "vary", "timeout_s"});

  SweepSpec spec;
  spec.source = source_name;
  spec.name =
      root["name"] ? reader.String(root["name"], "name") : fs::path(source_name).stem().string();
  // A bare file name (`trackbed sweep my.yaml`) has an empty directory: the working one.
  const fs::path dir =
      (file_dir.empty() ? fs::current_path() : fs::absolute(file_dir)).lexically_normal();
  spec.base_dir = dir;
  if (root["base_dir"]) {
    const fs::path b = reader.String(root["base_dir"], "base_dir");
    spec.base_dir = (b.is_absolute() ? b : dir / b).lexically_normal();
    if (!fs::is_directory(spec.base_dir)) {
      reader.Fail("base_dir", "no such folder: " + spec.base_dir.string());
    }
  }

  if (!root["scenarios"]) reader.Fail("scenarios", "missing (a list of scenario files)");
  const YAML::Node scenarios = reader.List(root["scenarios"], "scenarios");
  std::vector<fs::path> resolved;
  for (std::size_t i = 0; i < scenarios.size(); ++i) {
    const std::string key = Indexed("scenarios", i);
    const std::string s = reader.String(scenarios[i], key);
    const fs::path p = fs::path(s).is_absolute() ? fs::path(s) : spec.base_dir / s;
    const fs::path abs = p.lexically_normal();
    if (!fs::is_regular_file(abs)) reader.Fail(key, "no such file: " + abs.string());
    const auto same = std::find(resolved.begin(), resolved.end(), abs);
    if (same != resolved.end()) {
      reader.Fail(key,
                  "listed twice (also scenarios[" + std::to_string(same - resolved.begin()) + "])");
    }
    resolved.push_back(abs);
    spec.scenarios.push_back(s);
  }

  if (!root["seeds"]) reader.Fail("seeds", "missing (a list of seeds or {from: A, to: B})");
  const YAML::Node seeds = root["seeds"];
  if (seeds.IsMap()) {
    reader.OnlyKeys(seeds, "seeds", {"from", "to"});
    for (const char* k : {"from", "to"}) {
      if (!seeds[k]) reader.Fail("seeds", std::string("missing `") + k + "`");
    }
    const std::uint64_t from = reader.Unsigned(seeds["from"], "seeds.from");
    const std::uint64_t to = reader.Unsigned(seeds["to"], "seeds.to");
    if (to < from) reader.Fail("seeds.to", "must be >= from");
    if (to - from >= kMaxRangeValues) {
      reader.Fail("seeds", "more than " + std::to_string(kMaxRangeValues) + " seeds");
    }
    for (std::uint64_t s = from; s <= to; ++s) spec.seeds.push_back(s);
  } else if (seeds.IsSequence()) {
    reader.List(seeds, "seeds");
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      const std::uint64_t s = reader.Unsigned(seeds[i], Indexed("seeds", i));
      if (std::find(spec.seeds.begin(), spec.seeds.end(), s) != spec.seeds.end()) {
        reader.Fail(Indexed("seeds", i), "duplicate seed " + std::to_string(s));
      }
      spec.seeds.push_back(s);
    }
  } else {
    reader.Fail("seeds",
                std::string("expected a list of seeds or {from: A, to: B}, got ") + Kind(seeds));
  }

  if (root["set"]) {
    const YAML::Node set = reader.List(root["set"], "set");
    for (std::size_t i = 0; i < set.size(); ++i) {
      const std::string key = Indexed("set", i);
      const std::string text = reader.String(set[i], key);
      scenario::Override o;
      try {
        o = scenario::ParseOverride(text);
      } catch (const std::invalid_argument&) {
        reader.Fail(key, "expected key=value, got '" + text + "'");
      }
      CheckKey(reader, o.key, key);
      for (const scenario::Override& before : spec.set) {
        if (before.key == o.key) reader.Fail(key, "'" + o.key + "' is set twice");
      }
      spec.set.push_back(o);
    }
  }

  if (root["vary"]) {
    const YAML::Node vary = reader.List(root["vary"], "vary");
    for (std::size_t i = 0; i < vary.size(); ++i) {
      const std::string where = Indexed("vary", i);
      const YAML::Node axis_node = reader.Map(vary[i], where);
      reader.OnlyKeys(axis_node, where, {"key", "values", "range", "replicate"});
      if (!axis_node["key"]) reader.Fail(where, "missing `key`");
      SweepAxis axis;
      axis.key = reader.String(axis_node["key"], where + ".key");
      CheckKey(reader, axis.key, where + ".key");
      for (const scenario::Override& o : spec.set) {
        if (o.key == axis.key) reader.Fail(where + ".key", "'" + axis.key + "' is also in `set`");
      }
      for (const SweepAxis& other : spec.vary) {
        if (other.key == axis.key) reader.Fail(where + ".key", "'" + axis.key + "' varied twice");
      }
      const bool has_values = static_cast<bool>(axis_node["values"]);
      const bool has_range = static_cast<bool>(axis_node["range"]);
      if (has_values == has_range) reader.Fail(where, "give either `values` or `range`");
      if (has_values) {
        const YAML::Node values = reader.List(axis_node["values"], where + ".values");
        for (std::size_t k = 0; k < values.size(); ++k) {
          const std::string key = Indexed(where + ".values", k);
          if (values[k].IsNull()) reader.Fail(key, "null value");
          const std::string text = ValueText(values[k]);
          if (std::find(axis.values.begin(), axis.values.end(), text) != axis.values.end()) {
            reader.Fail(key, "duplicate value '" + text + "'");
          }
          axis.values.push_back(text);
        }
      } else {
        axis.values = RangeValues(reader, axis_node["range"], where + ".range");
      }
      if (axis_node["replicate"]) {
        const std::string r = reader.String(axis_node["replicate"], where + ".replicate");
        if (r != "true" && r != "false") {
          reader.Fail(where + ".replicate", "expected true or false, got '" + r + "'");
        }
        axis.replicate = r == "true";
      }
      spec.vary.push_back(axis);
    }
  }

  if (root["timeout_s"]) {
    const double t = reader.Number(root["timeout_s"], "timeout_s");
    if (!(t > 0)) reader.Fail("timeout_s", "must be > 0");
    spec.timeout_s = t;
  }
  return spec;
}

SweepSpec LoadSweep(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw SweepError(path.string(), "", "cannot read file");
  std::ostringstream text;
  text << f.rdbuf();
  return ParseSweep(text.str(), path.string(), path.parent_path());
}

std::string SweepToYaml(const SweepSpec& spec) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << YAML::DoubleQuoted << spec.name;
  out << YAML::Key << "base_dir" << YAML::Value << YAML::DoubleQuoted << spec.base_dir.string();
  out << YAML::Key << "scenarios" << YAML::Value << YAML::BeginSeq;
  for (const std::string& s : spec.scenarios) out << YAML::DoubleQuoted << s;
  out << YAML::EndSeq;
  out << YAML::Key << "seeds" << YAML::Value << YAML::Flow << spec.seeds;
  if (!spec.set.empty()) {
    out << YAML::Key << "set" << YAML::Value << YAML::BeginSeq;
    for (const scenario::Override& o : spec.set) out << YAML::DoubleQuoted << OverrideText(o);
    out << YAML::EndSeq;
  }
  if (!spec.vary.empty()) {
    out << YAML::Key << "vary" << YAML::Value << YAML::BeginSeq;
    for (const SweepAxis& a : spec.vary) {
      out << YAML::BeginMap;
      out << YAML::Key << "key" << YAML::Value << a.key;
      out << YAML::Key << "values" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (const std::string& v : a.values) {
        YAML::Node node = YAML::Load(v);
        if (node.IsScalar() || node.IsNull()) {
          out << v;  // as written: a string stays a string, `1.0` stays `1.0`
        } else {
          MakeFlow(node);
          out << node;
        }
      }
      out << YAML::EndSeq;
      if (a.replicate) out << YAML::Key << "replicate" << YAML::Value << true;
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  if (spec.timeout_s) {
    char buf[64];
    char* end = std::to_chars(buf, buf + sizeof(buf), *spec.timeout_s).ptr;
    out << YAML::Key << "timeout_s" << YAML::Value << std::string(buf, end);
  }
  out << YAML::EndMap;
  return "# Resolved copy of " + spec.source +
         " written by `trackbed sweep`: seeds and ranges listed,\n"
         "# scenario paths relative to base_dir. `trackbed sweep` on this file runs the same "
         "cells.\n" +
         std::string(out.c_str()) + "\n";
}

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
  return plan;
}

std::string SweepPlanJson(const SweepPlan& plan) {
  Json j;
  j["sweep"] = plan.name;
  j["timeout_s"] = plan.timeout_s ? Json(*plan.timeout_s) : Json();
  j["vary_keys"] = plan.vary_keys;
  j["replicate_keys"] = plan.replicate_keys;
  Json cells = Json::array();
  for (const SweepCell& c : plan.cells) {
    Json cell;
    cell["index"] = c.index;
    cell["name"] = c.name;
    cell["group"] = c.group;
    cell["scenario"] = c.scenario;
    cell["scenario_path"] = c.scenario_path.string();
    cell["seed"] = c.seed;
    Json vary = Json::object();
    for (const scenario::Override& o : c.varied) vary[o.key] = o.value;
    cell["vary"] = vary;
    Json set = Json::array();
    for (const scenario::Override& o : c.overrides) set.push_back(OverrideText(o));
    cell["set"] = set;
    cells.push_back(cell);
  }
  j["cells"] = cells;
  return j.dump(2) + "\n";
}

SweepPlan ParseSweepPlan(const std::string& json_text, const std::string& source_name) {
  const Json j = ParseJson(json_text, source_name);
  SweepPlan plan;
  plan.name = Get<std::string>(j, "sweep", source_name, "");
  if (j.contains("timeout_s") && !j["timeout_s"].is_null()) {
    plan.timeout_s = Get<double>(j, "timeout_s", source_name, "");
  }
  plan.vary_keys = Get<std::vector<std::string>>(j, "vary_keys", source_name, "");
  plan.replicate_keys = Get<std::vector<std::string>>(j, "replicate_keys", source_name, "");
  const Json cells = Get<Json>(j, "cells", source_name, "");
  if (!cells.is_array()) throw SweepError(source_name, "cells", "expected a list");
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const Json& c = cells[i];
    const std::string where = Indexed("cells", i);
    SweepCell cell;
    cell.index = Get<std::size_t>(c, "index", source_name, where);
    if (cell.index != i) throw SweepError(source_name, where + ".index", "out of order");
    cell.name = Get<std::string>(c, "name", source_name, where);
    cell.group = Get<std::string>(c, "group", source_name, where);
    cell.scenario = Get<std::string>(c, "scenario", source_name, where);
    cell.scenario_path = Get<std::string>(c, "scenario_path", source_name, where);
    cell.seed = Get<std::uint64_t>(c, "seed", source_name, where);
    const Json vary = Get<Json>(c, "vary", source_name, where);
    if (!vary.is_object()) throw SweepError(source_name, where + ".vary", "expected a map");
    for (const auto& [key, value] : vary.items()) {
      if (!value.is_string()) throw SweepError(source_name, where + ".vary." + key, "not text");
      cell.varied.push_back({key, value.get<std::string>()});
    }
    for (const std::string& s : Get<std::vector<std::string>>(c, "set", source_name, where)) {
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
    for (const scenario::Override& o : c.overrides) s += " --set " + OverrideText(o);
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
    const Json j = Json::parse(ReadTextFile(metrics));
    return j.is_object() && j.contains("status");
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
  Json j;
  j["cell"] = cell.name;
  j["index"] = cell.index;
  j["scenario"] = cell.scenario;
  j["seed"] = cell.seed;
  Json set = Json::array();
  for (const scenario::Override& o : cell.overrides) set.push_back(OverrideText(o));
  j["set"] = set;
  j["status"] = ToString(outcome.status);
  j["exit_code"] = outcome.exit_code ? Json(*outcome.exit_code) : Json();
  j["reason"] = outcome.reason;
  j["stderr_tail"] = outcome.stderr_tail;
  j["wall_time_s"] = outcome.wall_time_s;
  j["host"] = outcome.host;
  j["started_utc"] = outcome.started_utc;
  if (!outcome.slurm_job.empty()) j["slurm_job"] = outcome.slurm_job;
  return j.dump(2) + "\n";
}

CellOutcome ParseCellOutcome(const std::string& json_text, const std::string& source_name) {
  const Json j = ParseJson(json_text, source_name);
  CellOutcome o;
  const std::string status = Get<std::string>(j, "status", source_name, "");
  bool known = false;
  for (CellStatus s : {CellStatus::kPending, CellStatus::kOk, CellStatus::kFailed,
                       CellStatus::kTimedOut, CellStatus::kInterrupted}) {
    if (status == ToString(s)) {
      o.status = s;
      known = true;
    }
  }
  if (!known) throw SweepError(source_name, "status", "unknown status '" + status + "'");
  if (j.contains("exit_code") && !j["exit_code"].is_null()) {
    o.exit_code = Get<int>(j, "exit_code", source_name, "");
  }
  o.reason = Get<std::string>(j, "reason", source_name, "");
  o.stderr_tail = Get<std::string>(j, "stderr_tail", source_name, "");
  o.wall_time_s = Get<double>(j, "wall_time_s", source_name, "");
  o.host = Get<std::string>(j, "host", source_name, "");
  o.started_utc = Get<std::string>(j, "started_utc", source_name, "");
  if (j.contains("slurm_job")) o.slurm_job = Get<std::string>(j, "slurm_job", source_name, "");
  return o;
}

CellOutcome ReadCellOutcome(const fs::path& sweep_dir, const SweepCell& cell) {
  const fs::path path = CellJsonPath(sweep_dir, cell);
  if (!fs::exists(path)) return {};
  return ParseCellOutcome(ReadTextFile(path), path.string());
}

CellOutcome OutcomeFromMetrics(const std::string& metrics_json_text) {
  CellOutcome o;
  try {
    const Json j = Json::parse(metrics_json_text);
    const std::string status = j.at("status").get<std::string>();
    if (status == "completed") {
      o.status = CellStatus::kOk;
    } else {
      o.status = CellStatus::kFailed;
      const std::string why = j.contains("stop_reason") && j["stop_reason"].is_string()
                                  ? j["stop_reason"].get<std::string>()
                                  : status;
      o.reason = "run failed: " + why;
    }
  } catch (const std::exception& e) {
    o.status = CellStatus::kFailed;
    o.reason = std::string("unreadable metrics.json: ") + e.what();
  }
  return o;
}

void WriteFileAtomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  const auto fail = [&](const char* what) {
    throw std::runtime_error(tmp.string() + ": cannot " + what + ": " + std::strerror(errno));
  };
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("create");
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      fail("write");
    }
    done += static_cast<std::size_t>(n);
  }
  // On disk before the rename makes it visible: a power loss leaves the old file or
  // the whole new one.
  if (::fsync(fd) != 0) {
    ::close(fd);
    fail("sync");
  }
  if (::close(fd) != 0) fail("close");
  fs::rename(tmp, path);
  const int dir = ::open(path.parent_path().empty() ? "." : path.parent_path().c_str(),
                         O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

std::string ReadTextFile(const fs::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error(path.string() + ": cannot read");
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace trackbed::experiments
