// Sweep files through the config archive (sweep.h, docs/sweeps.md): reading, and the
// resolved copy a sweep folder keeps (DIR/sweep.yaml).
//
// The archive checks keys and types against the field lists below (SweepFileFields);
// what the values must satisfy — non-empty lists free of duplicates, existing
// scenario files, well-formed overrides, `seed` only from `seeds`, a key either fixed
// or varied — is checked after, in file order. An error names the file, the dotted
// key (`vary[1].range.step`) and the reason, in the archive's brief wording, which
// the sweep reader used before the archive.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "trackbed/common/archive.h"
#include "trackbed/experiments/sweep.h"

namespace trackbed::experiments {

namespace fs = std::filesystem;

namespace {

using archive::Field;
using archive::JoinIndex;
using archive::Node;

constexpr archive::Wording kWording = archive::Wording::kBrief;
// Most values a range or a seed range may expand to.
constexpr std::size_t kMaxRangeValues = 10000;
// Most cells a sweep may expand to (days of runs already): a few long ranges crossed
// would otherwise make billions of cells, minutes and gigabytes of ExpandSweep before
// anything is said.
constexpr std::size_t kMaxCells = 10000;

// ---------------------------------------------------------------------------
// The file's form. Optional fields tell a missing key from an empty value.

/// `range: {from: A, to: B, step: S}` of an axis.
struct RangeFields {
  std::optional<double> from, to, step;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("from", &from);
    a->Visit("to", &to);
    a->Visit("step", &step);
  }
};

/// `seeds: {from: A, to: B}`.
struct SeedRangeFields {
  std::optional<std::uint64_t> from, to;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("from", &from);
    a->Visit("to", &to);
  }
};

/// One entry of `vary`: values (any YAML, kept as parsed) or a range.
struct AxisFields {
  std::optional<std::string> key;
  std::optional<std::vector<Node>> values;
  std::optional<RangeFields> range;
  bool replicate = false;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("key", &key);
    a->Visit("values", &values, archive::kOmitEmpty);
    a->Visit("range", &range, archive::kOmitEmpty);
    a->Visit("replicate", &replicate, archive::kOmitEmpty);
  }
};

/// The whole file. `seeds` is a list or a range, told apart after reading.
struct SweepFileFields {
  std::optional<std::string> name, base_dir;
  std::vector<std::string> scenarios;
  Node seeds;
  std::optional<std::vector<std::string>> set;
  std::optional<std::vector<AxisFields>> vary;
  std::optional<double> timeout_s;
  std::optional<std::vector<SweepExpectation>> expect;

  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit("name", &name, archive::kOmitEmpty);
    a->Visit("base_dir", &base_dir, archive::kOmitEmpty);
    a->Visit("scenarios", &scenarios, Field{true, "a list of scenario files"});
    a->Visit("seeds", &seeds, Field{true, "a list of seeds or {from: A, to: B}"});
    a->Visit("set", &set, archive::kOmitEmpty);
    a->Visit("vary", &vary, archive::kOmitEmpty);
    a->Visit("timeout_s", &timeout_s, archive::kOmitEmpty);
    a->Visit("expect", &expect, archive::kOmitEmpty);
  }
};

// ---------------------------------------------------------------------------
// From the file's form to a SweepSpec.

/// Throws the SweepError of one file.
class Failer {
 public:
  explicit Failer(std::string source) : source_(std::move(source)) {}
  [[noreturn]] void operator()(const std::string& key, const std::string& reason) const {
    throw SweepError(source_, key, reason);
  }

 private:
  std::string source_;
};

SweepFileFields ReadSweepFile(const std::string& yaml_text, const Failer& fail) {
  SweepFileFields fields;
  try {
    const Node root = archive::ParseYaml(yaml_text);
    if (!root.IsMap()) {
      fail("", "expected a map of sweep keys, got " + archive::Describe(root, kWording));
    }
    archive::Read(root, "", kWording, &fields);
  } catch (const archive::SyntaxError& e) {
    fail("", "YAML syntax error at line " + std::to_string(e.line()) + ": " + e.detail());
  } catch (const archive::Error& e) {
    fail(e.path(), e.reason());
  }
  return fields;
}

// Flow style all the way down, so that a list value becomes one `--set` token.
void MakeFlow(Node& node) {
  if (!node.IsList() && !node.IsMap()) return;
  node.set_style(Node::Style::kFlow);
  for (Node& item : node.items()) MakeFlow(item);
  for (auto& entry : node.entries()) MakeFlow(entry.second);
}

// A value node as the text `--set key=` takes: scalars as written, lists and maps in
// flow style.
std::string ValueText(const Node& node) {
  if (node.IsScalar()) return node.text();
  Node copy = node;
  MakeFlow(copy);
  return archive::EmitYaml(copy);
}

// Checks `key=value` syntax of a key the way `--set` would, without a value.
void CheckKey(const Failer& fail, const std::string& key, const std::string& where) {
  // A key with '=' would split there: `--set a=b=0` sets `a` to `b=0`.
  bool valid = key.find('=') == std::string::npos;
  try {
    scenario::ParseOverride(key + "=0");
  } catch (const std::invalid_argument&) {
    valid = false;
  }
  if (!valid) fail(where, "'" + key + "' is not a dotted scenario key");
  if (key == "seed") fail(where, "the seed comes from `seeds`, not from an override");
}

// `from + k * step` printed with 12 significant digits (so 0.1 + 2 * 0.1 is 0.3),
// or as an integer when from, to and step are all integers.
std::vector<std::string> RangeValues(const RangeFields& range, const std::string& key,
                                     const Failer& fail) {
  for (const auto& [name, value] : {std::pair("from", range.from), std::pair("to", range.to)}) {
    if (!value) fail(key, std::string("missing `") + name + "`");
  }
  const double from = *range.from, to = *range.to, step = range.step.value_or(1.0);
  for (const auto& [name, value] :
       {std::pair("from", from), std::pair("to", to), std::pair("step", step)}) {
    if (!std::isfinite(value)) {
      fail(key + "." + name, "must be a finite number (got " + archive::FormatDouble(value) + ")");
    }
  }
  if (!(step > 0)) fail(key + ".step", "must be > 0");
  if (to < from) fail(key + ".to", "must be >= from");
  const double count = std::floor((to - from) / step * (1.0 + 1e-12) + 1e-9) + 1.0;
  if (count > static_cast<double>(kMaxRangeValues)) {
    fail(key, "more than " + std::to_string(kMaxRangeValues) + " values");
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

// `base_dir` of the file when given (relative to the file's folder), else the folder.
fs::path BaseDir(const std::optional<std::string>& base_dir, const fs::path& file_dir,
                 const Failer& fail) {
  // A bare file name (`trackbed sweep my.yaml`) has an empty directory: the working one.
  const fs::path dir =
      (file_dir.empty() ? fs::current_path() : fs::absolute(file_dir)).lexically_normal();
  if (!base_dir) return dir;
  if (base_dir->empty()) fail("base_dir", "must not be empty");
  const fs::path b = *base_dir;
  const fs::path resolved = (b.is_absolute() ? b : dir / b).lexically_normal();
  if (!fs::is_directory(resolved)) fail("base_dir", "no such folder: " + resolved.string());
  return resolved;
}

// Every scenario file exists, and none is listed twice.
void CheckScenarios(const std::vector<std::string>& scenarios, const fs::path& base_dir,
                    const Failer& fail) {
  if (scenarios.empty()) fail("scenarios", "must not be empty");
  std::vector<fs::path> resolved;
  for (std::size_t i = 0; i < scenarios.size(); ++i) {
    const std::string key = JoinIndex("scenarios", i);
    const std::string& s = scenarios[i];
    if (s.empty()) fail(key, "must not be empty");
    const fs::path p = fs::path(s).is_absolute() ? fs::path(s) : base_dir / s;
    const fs::path abs = p.lexically_normal();
    if (!fs::is_regular_file(abs)) fail(key, "no such file: " + abs.string());
    const auto same = std::find(resolved.begin(), resolved.end(), abs);
    if (same != resolved.end()) {
      fail(key, "listed twice (also scenarios[" + std::to_string(same - resolved.begin()) + "])");
    }
    resolved.push_back(abs);
  }
}

std::vector<std::uint64_t> Seeds(const Node& node, const Failer& fail) {
  std::vector<std::uint64_t> seeds;
  try {
    if (node.IsMap()) {
      SeedRangeFields range;
      archive::Read(node, "seeds", kWording, &range);
      if (!range.from) fail("seeds", "missing `from`");
      if (!range.to) fail("seeds", "missing `to`");
      if (*range.to < *range.from) fail("seeds.to", "must be >= from");
      if (*range.to - *range.from >= kMaxRangeValues) {
        fail("seeds", "more than " + std::to_string(kMaxRangeValues) + " seeds");
      }
      // Counted rather than `s <= to`, which never ends when `to` is the largest uint64.
      for (std::uint64_t k = 0; k <= *range.to - *range.from; ++k) {
        seeds.push_back(*range.from + k);
      }
      return seeds;
    }
    if (!node.IsList()) {
      fail("seeds", "expected a list of seeds or {from: A, to: B}, got " +
                        archive::Describe(node, kWording));
    }
    archive::Read(node, "seeds", kWording, &seeds);
  } catch (const archive::Error& e) {
    fail(e.path(), e.reason());
  }
  if (seeds.empty()) fail("seeds", "must not be empty");
  for (std::size_t i = 1; i < seeds.size(); ++i) {
    if (std::find(seeds.begin(), seeds.begin() + static_cast<long>(i), seeds[i]) !=
        seeds.begin() + static_cast<long>(i)) {
      fail(JoinIndex("seeds", i), "duplicate seed " + std::to_string(seeds[i]));
    }
  }
  return seeds;
}

// The fixed overrides of `set`.
std::vector<scenario::Override> FixedOverrides(const std::vector<std::string>& set,
                                               const Failer& fail) {
  if (set.empty()) fail("set", "must not be empty");
  std::vector<scenario::Override> overrides;
  for (std::size_t i = 0; i < set.size(); ++i) {
    const std::string key = JoinIndex("set", i);
    if (set[i].empty()) fail(key, "must not be empty");
    scenario::Override o;
    try {
      o = scenario::ParseOverride(set[i]);
    } catch (const std::invalid_argument&) {
      fail(key, "expected key=value, got '" + set[i] + "'");
    }
    CheckKey(fail, o.key, key);
    for (const scenario::Override& before : overrides) {
      if (before.key == o.key) fail(key, "'" + o.key + "' is set twice");
    }
    overrides.push_back(o);
  }
  return overrides;
}

// One axis of `vary`; `spec` holds the fixed overrides and the axes before it.
SweepAxis Axis(const AxisFields& fields, const std::string& where, const SweepSpec& spec,
               const Failer& fail) {
  if (!fields.key) fail(where, "missing `key`");
  if (fields.key->empty()) fail(where + ".key", "must not be empty");
  SweepAxis axis;
  axis.key = *fields.key;
  CheckKey(fail, axis.key, where + ".key");
  for (const scenario::Override& o : spec.set) {
    if (o.key == axis.key) fail(where + ".key", "'" + axis.key + "' is also in `set`");
  }
  for (const SweepAxis& other : spec.vary) {
    if (other.key == axis.key) fail(where + ".key", "'" + axis.key + "' varied twice");
  }
  if (fields.values.has_value() == fields.range.has_value()) {
    fail(where, "give either `values` or `range`");
  }
  if (fields.range) {
    axis.values = RangeValues(*fields.range, where + ".range", fail);
  } else {
    if (fields.values->empty()) fail(where + ".values", "must not be empty");
    for (std::size_t k = 0; k < fields.values->size(); ++k) {
      const std::string key = JoinIndex(where + ".values", k);
      if ((*fields.values)[k].IsNull()) fail(key, "null value");
      const std::string text = ValueText((*fields.values)[k]);
      if (std::find(axis.values.begin(), axis.values.end(), text) != axis.values.end()) {
        fail(key, "duplicate value '" + text + "'");
      }
      axis.values.push_back(text);
    }
  }
  axis.replicate = fields.replicate;
  return axis;
}

// Scenarios × each axis's values × seeds, counted without overflow, at most kMaxCells.
void CheckCellCount(const SweepSpec& spec, const Failer& fail) {
  std::size_t cells = spec.scenarios.size() * spec.seeds.size();
  bool too_many = cells > kMaxCells;
  for (const SweepAxis& a : spec.vary) {
    if (too_many || a.values.empty()) break;
    too_many = cells > kMaxCells / a.values.size();
    cells *= a.values.size();
  }
  if (too_many || cells > kMaxCells) {
    fail(spec.vary.empty() ? "seeds" : "vary",
         "the sweep expands to more than " + std::to_string(kMaxCells) +
             " cells (scenarios x values of each varied key x seeds)");
  }
}

}  // namespace

SweepSpec ParseSweep(const std::string& yaml_text, const std::string& source_name,
                     const fs::path& file_dir) {
  const Failer fail(source_name);
  const SweepFileFields fields = ReadSweepFile(yaml_text, fail);
  SweepSpec spec;
  spec.source = source_name;
  if (fields.name && fields.name->empty()) fail("name", "must not be empty");
  spec.name = fields.name ? *fields.name : fs::path(source_name).stem().string();
  spec.base_dir = BaseDir(fields.base_dir, file_dir, fail);
  CheckScenarios(fields.scenarios, spec.base_dir, fail);
  spec.scenarios = fields.scenarios;
  spec.seeds = Seeds(fields.seeds, fail);
  if (fields.set) spec.set = FixedOverrides(*fields.set, fail);
  if (fields.vary) {
    if (fields.vary->empty()) fail("vary", "must not be empty");
    for (std::size_t i = 0; i < fields.vary->size(); ++i) {
      spec.vary.push_back(Axis((*fields.vary)[i], JoinIndex("vary", i), spec, fail));
    }
  }
  CheckCellCount(spec, fail);
  if (fields.timeout_s) {
    const double t = *fields.timeout_s;
    if (!std::isfinite(t)) {
      fail("timeout_s", "must be a finite number (got " + archive::FormatDouble(t) + ")");
    }
    if (!(t > 0)) fail("timeout_s", "must be > 0");
    spec.timeout_s = t;
  }
  if (fields.expect) {
    if (fields.expect->empty()) fail("expect", "must not be empty");
    for (std::size_t i = 0; i < fields.expect->size(); ++i) {
      const SweepExpectation& e = (*fields.expect)[i];
      const std::string problem = e.Problem();
      if (problem.empty()) {
        if (!e.scenario.empty() && std::find(spec.scenarios.begin(), spec.scenarios.end(),
                                             e.scenario) == spec.scenarios.end()) {
          fail(JoinIndex("expect", i) + ".scenario",
               "'" + e.scenario + "' is not among the sweep's scenarios");
        }
        continue;
      }
      const std::size_t colon = problem.find(": ");
      fail(JoinIndex("expect", i) + "." + problem.substr(0, colon), problem.substr(colon + 2));
    }
    spec.expect = *fields.expect;
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

// The same fields, written with the styles the resolved copy has always had: names and
// paths double-quoted, seeds and values in flow style.
std::string SweepToYaml(const SweepSpec& spec) {
  SweepFileFields fields;
  fields.name = spec.name;
  fields.base_dir = spec.base_dir.string();
  fields.scenarios = spec.scenarios;
  fields.seeds = archive::Write(spec.seeds);
  if (!spec.set.empty()) fields.set.emplace();
  for (const scenario::Override& o : spec.set) fields.set->push_back(scenario::OverrideText(o));
  if (!spec.vary.empty()) fields.vary.emplace();
  for (const SweepAxis& a : spec.vary) {
    AxisFields& axis = fields.vary->emplace_back();
    axis.key = a.key;
    axis.values.emplace();
    for (const std::string& v : a.values) {
      // As written: a string stays a string, `1.0` stays `1.0`.
      Node value = archive::ParseYaml(v);
      if (value.IsScalar() || value.IsNull()) value = Node::Scalar(v, Node::Tag::kPlain);
      axis.values->push_back(std::move(value));
    }
    axis.replicate = a.replicate;
  }
  fields.timeout_s = spec.timeout_s;
  if (!spec.expect.empty()) fields.expect = spec.expect;

  Node node = archive::Write(fields);
  const auto quote = [](Node& n) { n.set_style(Node::Style::kDoubleQuoted); };
  quote(*node.Find("name"));
  quote(*node.Find("base_dir"));
  for (Node& s : node.Find("scenarios")->items()) quote(s);
  node.Find("seeds")->set_style(Node::Style::kFlow);
  if (Node* set = node.Find("set")) {
    for (Node& s : set->items()) quote(s);
  }
  if (Node* vary = node.Find("vary")) {
    for (Node& axis : vary->items()) MakeFlow(*axis.Find("values"));
  }
  return "# Resolved copy of " + spec.source +
         " written by `trackbed sweep`: seeds and ranges listed,\n"
         "# scenario paths relative to base_dir. `trackbed sweep` on this file runs the same "
         "cells.\n" +
         archive::EmitYaml(node) + "\n";
}

}  // namespace trackbed::experiments
