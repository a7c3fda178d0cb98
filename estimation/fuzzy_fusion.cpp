// Fuzzy fusion (see fuzzy_fusion.h).
#include "trackbed/estimation/fuzzy_fusion.h"

#include <fl/Headers.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "ham2012_fusion_fll.h"
#include "trackbed/common/option_error.h"

namespace trackbed::estimation {

void FusionOptions::Validate() const {
  option_check::NonNegative("weight_rise_time_s", weight_rise_time_s);
  option_check::Positive("wheel_speed_std_mps", wheel_speed_std_mps);
  option_check::Positive("wheel_lateral_speed_std_mps", wheel_lateral_speed_std_mps);
  if (!(gate_probability > 0.0 && gate_probability < 1.0)) {
    throw OptionError("gate_probability",
                      "must be in (0, 1) (got " + option_check::Describe(gate_probability) + ")");
  }
}

FuzzyFusionWeight::FuzzyFusionWeight(const std::string& fll_text, const std::string& source) {
  try {
    engine_.reset(fl::FllImporter().fromString(fll_text));
  } catch (const std::exception& e) {
    throw std::invalid_argument(source + ": not a valid FLL engine: " + e.what());
  }
  std::string status;
  if (!engine_->isReady(&status)) {
    throw std::invalid_argument(source + ": fuzzy engine not ready: " + status);
  }
  slip_ = engine_->hasInputVariable("slip_velocity") ? engine_->getInputVariable("slip_velocity")
                                                     : nullptr;
  features_ =
      engine_->hasInputVariable("features") ? engine_->getInputVariable("features") : nullptr;
  w_ = engine_->hasOutputVariable("w") ? engine_->getOutputVariable("w") : nullptr;
  if (!slip_ || !features_ || !w_) {
    throw std::invalid_argument(
        source + ": the engine needs inputs slip_velocity and features and output w");
  }
}

FuzzyFusionWeight::FuzzyFusionWeight()
    : FuzzyFusionWeight(kHam2012FusionFll, "built-in ham2012_fusion.fll") {}

FuzzyFusionWeight FuzzyFusionWeight::FromFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot read fuzzy rule file");
  std::ostringstream text;
  text << in.rdbuf();
  return FuzzyFusionWeight(text.str(), path.string());
}

FuzzyFusionWeight::~FuzzyFusionWeight() = default;
FuzzyFusionWeight::FuzzyFusionWeight(FuzzyFusionWeight&&) noexcept = default;
FuzzyFusionWeight& FuzzyFusionWeight::operator=(FuzzyFusionWeight&&) noexcept = default;

const char* FuzzyFusionWeight::DefaultRules() { return kHam2012FusionFll; }

double FuzzyFusionWeight::Weight(double slip_velocity_mps, double features) {
  slip_->setValue(
      std::clamp(std::abs(slip_velocity_mps), slip_->getMinimum(), slip_->getMaximum()));
  features_->setValue(std::clamp(features, features_->getMinimum(), features_->getMaximum()));
  engine_->process();
  const double w = w_->getValue();
  return std::isfinite(w) ? std::clamp(w, 0.0, 1.0) : 1.0;
}

void FusedOdometry::Add(const geometry::Pose2& wheel, const std::optional<geometry::Pose2>& vo,
                        double w) {
  if (!vo) {
    pose_ = Compose(pose_, wheel);
    return;
  }
  const geometry::Pose2 blended{w * wheel.x + (1 - w) * vo->x, w * wheel.y + (1 - w) * vo->y,
                                w * wheel.yaw + (1 - w) * geometry::WrapAngle(vo->yaw)};
  pose_ = Compose(pose_, blended);
}

}  // namespace trackbed::estimation
