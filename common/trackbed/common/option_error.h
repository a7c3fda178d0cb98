// Errors for invalid options structs.
//
// Every options struct in trackbed validates itself once (docs/architecture.md) and
// throws OptionError naming the offending field. The scenario reader catches it
// and prefixes the file and the dotted key, so a user sees
// `scenes/x.yaml: robot.vehicle.mass_kg: must be > 0 (got -3)`.
#pragma once

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace trackbed {

/// An invalid value in an options struct: `field` is the struct member's name
/// (which is also its scenario key), `reason` says what is wrong.
class OptionError : public std::invalid_argument {
 public:
  OptionError(std::string field, std::string reason)
      : std::invalid_argument(field + ": " + reason),
        field_(std::move(field)),
        reason_(std::move(reason)) {}

  const std::string& field() const { return field_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string field_;
  std::string reason_;
};

namespace option_check {

inline std::string Describe(double value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

/// Throws unless `value` is finite and > 0.
inline void Positive(const char* field, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw OptionError(field, "must be > 0 (got " + Describe(value) + ")");
  }
}

/// Throws unless `value` is finite and >= 0.
inline void NonNegative(const char* field, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw OptionError(field, "must be >= 0 (got " + Describe(value) + ")");
  }
}

/// Throws unless lo <= value <= hi.
inline void InRange(const char* field, double value, double lo, double hi) {
  if (!(std::isfinite(value) && value >= lo && value <= hi)) {
    throw OptionError(field, "must be in [" + Describe(lo) + ", " + Describe(hi) + "] (got " +
                                 Describe(value) + ")");
  }
}

/// Throws unless `value` is 0 (a feature turned off) or finite and >= `minimum`.
inline void OffOrAtLeast(const char* field, double value, double minimum) {
  if (!(value == 0.0 || (std::isfinite(value) && value >= minimum))) {
    throw OptionError(
        field, "must be 0 (off) or >= " + Describe(minimum) + " (got " + Describe(value) + ")");
  }
}

/// Throws unless the count `value` >= `minimum`.
inline void AtLeast(const char* field, int value, int minimum) {
  if (value < minimum) {
    throw OptionError(
        field, "must be >= " + std::to_string(minimum) + " (got " + std::to_string(value) + ")");
  }
}

/// Throws unless value is finite (any sign).
inline void Finite(const char* field, double value) {
  if (!std::isfinite(value)) {
    throw OptionError(field, "must be a finite number (got " + Describe(value) + ")");
  }
}

}  // namespace option_check
}  // namespace trackbed

namespace trackbed::option_check {

/// Validates a nested options struct, prefixing its field names with `prefix.`
/// so the error names the full dotted path.
template <typename Options>
void Nested(const std::string& prefix, const Options& options) {
  try {
    options.Validate();
  } catch (const OptionError& e) {
    throw OptionError(prefix + "." + e.field(), e.reason());
  }
}

}  // namespace trackbed::option_check
