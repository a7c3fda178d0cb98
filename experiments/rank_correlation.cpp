// Rank correlation and rank violation (see rank_correlation.h).
#include "trackbed/experiments/rank_correlation.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace trackbed::experiments {
namespace {

void CheckPair(const std::vector<double>& x, const std::vector<double>& y, const char* what) {
  if (x.size() != y.size()) {
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(x.size()) +
                                " values against " + std::to_string(y.size()));
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      throw std::invalid_argument(std::string(what) + ": item " + std::to_string(i) +
                                  " is not finite");
    }
  }
}

}  // namespace

std::vector<double> AverageRanks(const std::vector<double>& x) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&x](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  std::vector<double> ranks(x.size());
  std::size_t begin = 0;
  while (begin < order.size()) {
    std::size_t end = begin + 1;
    while (end < order.size() && x[order[end]] == x[order[begin]]) ++end;
    // Positions begin..end-1 (0-based) hold equal values: ranks begin+1..end, mean below.
    const double mean_rank = 0.5 * static_cast<double>(begin + 1 + end);
    for (std::size_t k = begin; k < end; ++k) ranks[order[k]] = mean_rank;
    begin = end;
  }
  return ranks;
}

double PearsonR(const std::vector<double>& x, const std::vector<double>& y) {
  CheckPair(x, y, "PearsonR");
  const std::size_t n = x.size();
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(n);
  const double my = std::accumulate(y.begin(), y.end(), 0.0) / static_cast<double>(n);
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (sxx <= 0.0 || syy <= 0.0) return std::numeric_limits<double>::quiet_NaN();
  return std::clamp(sxy / std::sqrt(sxx * syy), -1.0, 1.0);
}

double SpearmanRho(const std::vector<double>& x, const std::vector<double>& y) {
  CheckPair(x, y, "SpearmanRho");
  return PearsonR(AverageRanks(x), AverageRanks(y));
}

double MeanMaximumRankViolation(const std::vector<double>& real, const std::vector<double>& sim) {
  CheckPair(real, sim, "MeanMaximumRankViolation");
  const std::size_t n = real.size();
  if (n < 2) return 0.0;
  const auto [lo, hi] = std::minmax_element(real.begin(), real.end());
  const double range = *hi - *lo;
  if (range <= 0.0) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double worst = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      if ((sim[i] < sim[j]) != (real[i] < real[j])) {
        worst = std::max(worst, std::abs(real[i] - real[j]));
      }
    }
    sum += worst / range;
  }
  return sum / static_cast<double>(n);
}

}  // namespace trackbed::experiments
