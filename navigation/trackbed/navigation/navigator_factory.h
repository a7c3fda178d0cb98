// Builds a navigator by method name (`navigation.method` in scenario files):
// "gauss_newton_subgoal", "potential_field" or "dwa".
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "trackbed/navigation/dynamic_window.h"
#include "trackbed/navigation/gauss_newton_controller.h"
#include "trackbed/navigation/navigation_setup.h"
#include "trackbed/navigation/navigator.h"
#include "trackbed/navigation/potential_field.h"
#include "trackbed/navigation/subgoal_planner.h"

namespace trackbed::navigation {

/// Options of every method; each navigator reads the sections it needs.
struct NavigatorOptions {
  NavigationSetup setup;                  ///< Robot, control period, goal tolerance.
  ProgressCheckerOptions progress;        ///< When a run without progress ends (kStalled).
  GaussNewtonOptions gauss_newton;        ///< "gauss_newton_subgoal": the controller …
  SubgoalOptions subgoal;                 ///< … and its sub-goal switcher.
  PotentialFieldOptions potential_field;  ///< "potential_field".
  DynamicWindowOptions dwa;               ///< "dwa".

  /// Throws OptionError naming the first invalid field as a dotted path.
  void Validate() const;
};

/// The accepted method names, in a fixed order.
const std::vector<std::string>& NavigationMethodNames();

/// A navigator for `method` driving to `goal`. Throws std::invalid_argument naming the
/// method (and the accepted names) for an unknown one, OptionError for invalid options.
std::unique_ptr<Navigator> MakeNavigator(const std::string& method, const NavigatorOptions& options,
                                         const Pose2& goal);

}  // namespace trackbed::navigation
