// The transfer study's figures (see transfer_study.h).
#include "trackbed/experiments/transfer_study.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>

#include "trackbed/common/median.h"
#include "trackbed/common/option_error.h"
#include "trackbed/common/random.h"
#include "trackbed/experiments/rank_correlation.h"

namespace trackbed::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A side prepared for resampling: each configuration's values grouped by unit — a block
// of block_frames consecutive frames of one sequence (the whole sequence without frame
// indices) — with the same unit numbers for every configuration.
struct Units {
  std::vector<std::vector<std::vector<double>>> values;  // [configuration][unit]
  std::vector<std::vector<int>> of_sequence;             // [sequence] → its units
  std::vector<long> block;                               // [unit] → block index
  bool has_frames = true;
};

Units Prepare(const OutcomeTable& table, const std::vector<std::string>& configurations,
              int block_frames) {
  Units u;
  std::map<std::pair<std::string, long>, int> unit_of;  // (sequence, block) → unit
  std::map<std::string, int> sequence_of;
  for (const std::string& name : configurations) {
    for (const SequenceOutcome& s : table.at(name)) {
      if (s.frames.empty()) u.has_frames = false;
      for (std::size_t k = 0; k < s.values.size(); ++k) {
        const long block = s.frames.empty() ? 0 : s.frames[k] / block_frames;
        if (unit_of.count({s.sequence, block})) continue;
        const int id = static_cast<int>(u.block.size());
        unit_of[{s.sequence, block}] = id;
        u.block.push_back(block);
        const auto [it, added] =
            sequence_of.emplace(s.sequence, static_cast<int>(u.of_sequence.size()));
        if (added) u.of_sequence.emplace_back();
        u.of_sequence[static_cast<std::size_t>(it->second)].push_back(id);
      }
    }
  }
  u.values.assign(configurations.size(), std::vector<std::vector<double>>(u.block.size()));
  for (std::size_t c = 0; c < configurations.size(); ++c) {
    for (const SequenceOutcome& s : table.at(configurations[c])) {
      for (std::size_t k = 0; k < s.values.size(); ++k) {
        const long block = s.frames.empty() ? 0 : s.frames[k] / block_frames;
        u.values[c][static_cast<std::size_t>(unit_of.at({s.sequence, block}))].push_back(
            s.values[k]);
      }
    }
  }
  return u;
}

// Each configuration's median over the units drawn (a unit drawn twice counts twice).
std::vector<double> Outcomes(const Units& u, const std::vector<int>& draw) {
  std::vector<double> out(u.values.size());
  std::vector<double> pooled;
  for (std::size_t c = 0; c < u.values.size(); ++c) {
    pooled.clear();
    for (int unit : draw) {
      const std::vector<double>& v = u.values[c][static_cast<std::size_t>(unit)];
      pooled.insert(pooled.end(), v.begin(), v.end());
    }
    out[c] = pooled.empty() ? kNaN : Median(pooled);
  }
  return out;
}

std::vector<int> AllUnits(const Units& u) {
  std::vector<int> all;
  for (const std::vector<int>& units : u.of_sequence)
    all.insert(all.end(), units.begin(), units.end());
  return all;
}

// Each sequence's units drawn with replacement, as many as it has.
std::vector<int> DrawUnits(const Units& u, random::Generator& rng) {
  std::vector<int> draw;
  for (const std::vector<int>& units : u.of_sequence) {
    for (std::size_t k = 0; k < units.size(); ++k)
      draw.push_back(units[rng.UniformIndex(units.size())]);
  }
  return draw;
}

std::vector<double> Pick(const std::vector<double>& x, const std::vector<std::size_t>& index) {
  std::vector<double> out;
  out.reserve(index.size());
  for (std::size_t i : index) out.push_back(x[i]);
  return out;
}

// The three measures of one resample; NaN where it has none.
struct Triple {
  double spearman = kNaN, pearson = kNaN, mmrv = kNaN;
};
Triple Measures(const std::vector<double>& real, const std::vector<double>& sim) {
  for (std::size_t i = 0; i < real.size(); ++i) {
    if (!std::isfinite(real[i]) || !std::isfinite(sim[i])) return {};
  }
  if (real.size() < 3) return {};
  return {SpearmanRho(real, sim), PearsonR(real, sim), MeanMaximumRankViolation(real, sim)};
}

// The resamples of one kind of interval, per measure.
struct Samples {
  std::vector<double> spearman, pearson, mmrv;
  void Add(const Triple& t) {
    if (std::isfinite(t.spearman)) spearman.push_back(t.spearman);
    if (std::isfinite(t.pearson)) pearson.push_back(t.pearson);
    if (std::isfinite(t.mmrv)) mmrv.push_back(t.mmrv);
  }
};

Interval Percentiles(std::vector<double> x, double level) {
  Interval in;
  in.resamples = static_cast<int>(x.size());
  if (x.empty()) return in;
  std::sort(x.begin(), x.end());
  const auto at = [&x](double q) {
    const double pos = q * static_cast<double>(x.size() - 1);
    const std::size_t i = static_cast<std::size_t>(std::floor(pos));
    const std::size_t j = std::min(i + 1, x.size() - 1);
    return x[i] + (pos - static_cast<double>(i)) * (x[j] - x[i]);
  };
  in.low = at(0.5 * (1.0 - level));
  in.high = at(1.0 - 0.5 * (1.0 - level));
  return in;
}

// The subset's indices drawn with replacement, as many as it has.
std::vector<std::size_t> DrawIndices(const std::vector<std::size_t>& subset,
                                     random::Generator& rng) {
  std::vector<std::size_t> draw;
  for (std::size_t k = 0; k < subset.size(); ++k)
    draw.push_back(subset[rng.UniformIndex(subset.size())]);
  return draw;
}

// The agreement over `subset` with its bootstrap intervals.
Agreement Agree(const TransferFigures& f, const std::vector<std::size_t>& subset, const Units& real,
                const Units& sim, const TransferOptions& options) {
  Agreement a;
  for (std::size_t i : subset) a.configurations.push_back(f.configurations[i]);
  const Triple point = Measures(Pick(f.real, subset), Pick(f.sim, subset));
  a.spearman.value = point.spearman;
  a.pearson.value = point.pearson;
  a.mmrv.value = point.mmrv;
  if (subset.size() < 3) return a;
  random::Generator rng(options.seed);
  Samples frames, configurations, both;
  for (int rep = 0; rep < options.resamples; ++rep) {
    const std::vector<double> r = Outcomes(real, DrawUnits(real, rng));
    const std::vector<double> s = Outcomes(sim, DrawUnits(sim, rng));
    const std::vector<std::size_t> draw = DrawIndices(subset, rng);
    frames.Add(Measures(Pick(r, subset), Pick(s, subset)));
    configurations.Add(Measures(Pick(f.real, draw), Pick(f.sim, draw)));
    both.Add(Measures(Pick(r, draw), Pick(s, draw)));
  }
  const auto fill = [&options](Measure* m, std::vector<double> Samples::*member, Samples& fr,
                               Samples& co, Samples& bo) {
    m->frames = Percentiles(fr.*member, options.level);
    m->configurations = Percentiles(co.*member, options.level);
    m->both = Percentiles(bo.*member, options.level);
  };
  fill(&a.spearman, &Samples::spearman, frames, configurations, both);
  fill(&a.pearson, &Samples::pearson, frames, configurations, both);
  fill(&a.mmrv, &Samples::mmrv, frames, configurations, both);
  return a;
}

SplitHalf Split(const Units& u) {
  SplitHalf h;
  if (!u.has_frames || u.values.size() < 3) return h;
  std::vector<int> even, odd;
  for (int unit : AllUnits(u)) {
    (u.block[static_cast<std::size_t>(unit)] % 2 == 0 ? even : odd).push_back(unit);
  }
  const std::vector<double> a = Outcomes(u, even), b = Outcomes(u, odd);
  const Triple t = Measures(a, b);
  h.available = true;
  h.spearman = t.spearman;
  h.pearson = t.pearson;
  const auto step_up = [](double x) { return std::isfinite(x) ? 2.0 * x / (1.0 + x) : kNaN; };
  h.spearman_full = step_up(h.spearman);
  h.pearson_full = step_up(h.pearson);
  return h;
}

// The configurations in both tables, by name; throws naming the first in only one.
std::vector<std::string> SharedConfigurations(const OutcomeTable& real, const OutcomeTable& sim) {
  for (const auto& [name, sequences] : real) {
    if (!sim.count(name)) {
      throw std::invalid_argument("configuration '" + name +
                                  "' has real outcomes but no simulated ones");
    }
  }
  std::vector<std::string> names;
  for (const auto& [name, sequences] : sim) {
    if (!real.count(name)) {
      throw std::invalid_argument("configuration '" + name +
                                  "' has simulated outcomes but no real ones");
    }
    names.push_back(name);
  }
  if (names.size() < 3) {
    throw std::invalid_argument("need at least 3 configurations, got " +
                                std::to_string(names.size()));
  }
  return names;
}

// The configurations within near_best_factor of the best real outcome.
std::vector<std::size_t> NearBest(const std::vector<double>& real, const TransferOptions& o) {
  const double best = o.higher_is_better ? *std::max_element(real.begin(), real.end())
                                         : *std::min_element(real.begin(), real.end());
  std::vector<std::size_t> subset;
  if (!(best > 0.0)) return subset;
  for (std::size_t i = 0; i < real.size(); ++i) {
    const bool near = o.higher_is_better ? real[i] * o.near_best_factor >= best
                                         : real[i] <= o.near_best_factor * best;
    if (near) subset.push_back(i);
  }
  return subset;
}

}  // namespace

double ConfigurationOutcome(const std::vector<SequenceOutcome>& sequences) {
  std::vector<double> pooled;
  for (const SequenceOutcome& s : sequences)
    pooled.insert(pooled.end(), s.values.begin(), s.values.end());
  return pooled.empty() ? kNaN : Median(pooled);
}

void TransferOptions::Validate() const {
  option_check::AtLeast("resamples", resamples, 100);
  option_check::AtLeast("block_frames", block_frames, 1);
  if (!(near_best_factor >= 1.0 && std::isfinite(near_best_factor))) {
    throw OptionError("near_best_factor",
                      "must be >= 1 (got " + option_check::Describe(near_best_factor) + ")");
  }
  if (!(level > 0.0 && level < 1.0)) {
    throw OptionError("level", "must be in (0, 1) (got " + option_check::Describe(level) + ")");
  }
}

TransferFigures TransferStudy(const OutcomeTable& real, const OutcomeTable& sim,
                              const TransferOptions& options) {
  options.Validate();
  TransferFigures f;
  f.options = options;
  f.configurations = SharedConfigurations(real, sim);
  for (const std::string& name : f.configurations) {
    f.real.push_back(ConfigurationOutcome(real.at(name)));
    f.sim.push_back(ConfigurationOutcome(sim.at(name)));
    if (!std::isfinite(f.real.back()) || !std::isfinite(f.sim.back())) {
      throw std::invalid_argument("configuration '" + name + "' has no " +
                                  (std::isfinite(f.real.back()) ? "simulated" : "real") +
                                  " values");
    }
  }
  const Units real_units = Prepare(real, f.configurations, options.block_frames);
  const Units sim_units = Prepare(sim, f.configurations, options.block_frames);
  std::vector<std::size_t> all(f.configurations.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  f.all = Agree(f, all, real_units, sim_units, options);
  f.near_best = Agree(f, NearBest(f.real, options), real_units, sim_units, options);
  f.real_ceiling = Split(real_units);
  f.sim_ceiling = Split(sim_units);
  return f;
}

}  // namespace trackbed::experiments
