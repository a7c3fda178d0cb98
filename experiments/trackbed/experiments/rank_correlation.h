// How well one set of outcomes ranks items as another does: Spearman's rank correlation
// ρ (ties given their average rank), Pearson's r, and the mean maximum rank violation
// (MMRV) of SIMPLER (Li et al. 2024, "Evaluating Real-World Robot Manipulation Policies
// in Simulation"), here with each violation weighted by the real outcomes' difference
// over their range, so that it is in [0, 1] whatever the outcome's unit. The measures
// robot-learning simulators use for whether their verdicts transfer to the real robot
// (Kadian et al., RA-L 2020: the Sim2Real Correlation Coefficient, a Pearson r);
// docs/transfer.md.
//
// Every function takes the two outcomes of the same items in the same order, finite,
// and throws std::invalid_argument for lists of different sizes or a non-finite value.
#pragma once

#include <vector>

namespace trackbed::experiments {

/// The 1-based ranks of x in ascending order, tied values given the mean of the ranks
/// they span ({10, 20, 20, 30} → {1, 2.5, 2.5, 4}).
std::vector<double> AverageRanks(const std::vector<double>& x);

/// Pearson's product-moment correlation of x and y; NaN when there are fewer than 2
/// items or either list has no spread (all values equal).
double PearsonR(const std::vector<double>& x, const std::vector<double>& y);

/// Spearman's ρ: PearsonR of the average ranks (so ties are handled exactly); NaN as
/// PearsonR.
double SpearmanRho(const std::vector<double>& x, const std::vector<double>& y);

/// MMRV = (1/N) Σ_i max_j RV(i, j), RV(i, j) = |real_i − real_j| / (max real − min
/// real) when the simulated outcomes order i and j otherwise than the real ones
/// ((sim_i < sim_j) ≠ (real_i < real_j), SIMPLER's test), else 0: for each item, the
/// worst real difference the simulation got the wrong way round, averaged. 0 when the
/// orders agree, at most 1; 0 for fewer than 2 items or real outcomes all equal. The
/// direction of "better" does not matter (both lists are compared as they are).
double MeanMaximumRankViolation(const std::vector<double>& real, const std::vector<double>& sim);

}  // namespace trackbed::experiments
