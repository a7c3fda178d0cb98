// Whether the testbed's verdicts transfer: the outcomes of many configurations (settings
// or methods) measured in simulation and on real data, and how well the simulated
// outcomes rank the configurations as the real ones do (docs/transfer.md).
//
// An outcome table holds, for each configuration, the per-frame values of one metric
// (e.g. VO's frame-to-frame translation error) on one or more sequences (seeds of a
// simulated run, real logs). A configuration's outcome is the median of all its values.
// The figures (TransferStudy): Spearman's ρ, Pearson's r and the MMRV between the real
// and the simulated outcomes (rank_correlation.h), with percentile bootstrap intervals
// that resample frames (blocks of consecutive frames, the same draw for every
// configuration: their errors on a frame are paired), configurations, and both; the same
// on the configurations near the best on real data (poor ones are easy to rank); and the
// ceiling — how well the real outcomes rank the configurations against themselves, the
// correlation of the outcomes on alternating blocks of frames (split-half), and its
// Spearman–Brown step-up to the full length.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace trackbed::experiments {

/// One sequence's per-frame values of a configuration.
struct SequenceOutcome {
  std::string sequence;  ///< its name (a seed's folder, a log's name)
  /// Frame index of each value, >= 0; empty when the table has no frame column (then
  /// neither frames can be resampled nor halves split).
  std::vector<long> frames;
  std::vector<double> values;  ///< finite
};

/// A side's outcomes: configuration name → its sequences.
using OutcomeTable = std::map<std::string, std::vector<SequenceOutcome>>;

/// The median of all of a configuration's values over its sequences.
double ConfigurationOutcome(const std::vector<SequenceOutcome>& sequences);

/// Options of TransferStudy.
struct TransferOptions {
  /// Bootstrap resamples per interval, >= 100.
  int resamples = 2000;
  /// Seed of the bootstrap's generator (random::Generator): the same seed and tables give
  /// the same intervals.
  std::uint64_t seed = 1;
  /// Frames resampled and split together, >= 1: consecutive frames share features, so
  /// their errors are not independent (5 frames: half a second at 10 Hz).
  int block_frames = 5;
  /// The near-best subset: configurations whose real outcome is within this factor of
  /// the best (lower is better: <= factor × best; higher: >= best / factor), >= 1.
  double near_best_factor = 1.5;
  /// Whether a higher outcome is better (success rates); else lower (errors). Outcomes
  /// must then be positive for the near-best subset to be formed.
  bool higher_is_better = false;
  /// Two-sided level of the intervals, in (0, 1).
  double level = 0.95;

  /// Throws OptionError naming the first invalid field.
  void Validate() const;
};

/// A percentile bootstrap interval; `resamples` counts the resamples that gave a value
/// (a resample whose outcomes have no spread has no correlation).
struct Interval {
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
  int resamples = 0;
};

/// One measure with its intervals.
struct Measure {
  double value = std::numeric_limits<double>::quiet_NaN();
  Interval frames;          ///< frames resampled, configurations fixed
  Interval configurations;  ///< configurations resampled, frames fixed
  Interval both;            ///< both resampled: the interval to quote
};

/// The agreement over a set of configurations.
struct Agreement {
  std::vector<std::string> configurations;
  Measure spearman, pearson, mmrv;
};

/// The split-half correlation of one side's outcomes with themselves.
struct SplitHalf {
  bool available = false;  ///< false without frame indices or with < 3 configurations
  double spearman = std::numeric_limits<double>::quiet_NaN();
  double pearson = std::numeric_limits<double>::quiet_NaN();
  /// Spearman–Brown: 2ρ / (1 + ρ), the correlation expected of the full length.
  double spearman_full = std::numeric_limits<double>::quiet_NaN();
  double pearson_full = std::numeric_limits<double>::quiet_NaN();
};

struct TransferFigures {
  TransferOptions options;
  std::vector<std::string> configurations;  ///< in name order
  std::vector<double> real, sim;            ///< each configuration's outcome
  Agreement all, near_best;
  SplitHalf real_ceiling, sim_ceiling;
};

/// The figures of `real` against `sim`. Throws std::invalid_argument when a
/// configuration is in one table but not the other (naming it and the side), a
/// configuration has no values, or fewer than 3 configurations are shared; OptionError
/// for invalid options.
TransferFigures TransferStudy(const OutcomeTable& real, const OutcomeTable& sim,
                              const TransferOptions& options = {});

}  // namespace trackbed::experiments
