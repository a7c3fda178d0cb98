// A user's own commander, as a test writes one: replays recorded track speeds from a
// CSV file (header `t,left_mps,right_mps`, one row per change, times not decreasing),
// each row held until the next. Needs nothing of trackbed but the Commander interface.
#pragma once

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "trackbed/runner/commander.h"

namespace trackbed::testing {

class ReplayCommander : public runner::Commander {
 public:
  /// Reads `csv`; `period_s` is the control period at which the rows are looked up.
  ReplayCommander(const std::string& csv, double period_s) : period_s_(period_s) {
    std::ifstream in(csv);
    std::string line;
    if (!std::getline(in, line) || line != "t,left_mps,right_mps") {
      throw std::invalid_argument(csv + ": expected the header t,left_mps,right_mps");
    }
    while (std::getline(in, line)) {
      Row r;
      char comma1 = 0, comma2 = 0;
      std::istringstream fields(line);
      if (!(fields >> r.t_s >> comma1 >> r.left_mps >> comma2 >> r.right_mps) || comma1 != ',' ||
          comma2 != ',') {
        throw std::invalid_argument(csv + ": cannot read the row \"" + line + "\"");
      }
      rows_.push_back(r);
    }
  }

  double period_s() const override { return period_s_; }

  runner::ControlOutput Update(const runner::ControlInput& input) override {
    while (next_ < rows_.size() && rows_[next_].t_s <= input.t_s + 1e-9) ++next_;
    runner::ControlOutput out;
    if (next_ > 0) out.tracks = {rows_[next_ - 1].left_mps, rows_[next_ - 1].right_mps};
    return out;
  }

 private:
  struct Row {
    double t_s = 0.0, left_mps = 0.0, right_mps = 0.0;
  };
  double period_s_;
  std::vector<Row> rows_;
  std::size_t next_ = 0;
};

}  // namespace trackbed::testing
