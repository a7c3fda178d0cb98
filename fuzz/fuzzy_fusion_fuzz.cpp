// Fuzzes fuzzy rule files (fuzzy_fusion.h): FuzzyFusionWeight from the input as FLL text,
// and, where it constructs, Weight at a few points inside, on and beyond the inputs'
// ranges. The FLL parser itself is fuzzylite's (not instrumented here): what is ours is
// the check that the engine is usable, on which Weight relies.
//
// Finding: a crash, a sanitizer report, a hang, an exception other than
// std::invalid_argument from the constructor, any exception from Weight (documented as
// none), or a weight outside [0, 1].
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "trackbed/estimation/fuzzy_fusion.h"

// fuzzylite 6.0 (Debian's, not ours) leaks a rule's antecedent when the rule does not
// load (fl::Antecedent::load, 48 bytes per bad rule): reported upstream's business, and
// without this every run would stop at the first bad rule.
extern "C" const char* __lsan_default_suppressions() { return "leak:libfuzzylite.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::optional<trackbed::estimation::FuzzyFusionWeight> weight;
  try {
    weight.emplace(text, "fuzz.fll");
  } catch (const std::invalid_argument&) {
    return 0;
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const std::pair<double, double> points[] = {{0.0, 0.0},    {0.05, 30.0}, {0.3, 120.0},
                                              {-0.2, 500.0}, {1e6, -1.0},  {kInf, kInf}};
  for (const auto& [slip, features] : points) {
    const double w = weight->Weight(slip, features);
    if (!(w >= 0.0 && w <= 1.0)) {
      std::fprintf(stderr, "fuzzy_fusion_fuzz: FINDING: Weight(%g, %g) = %g\n", slip, features, w);
      std::abort();
    }
  }
  return 0;
}
