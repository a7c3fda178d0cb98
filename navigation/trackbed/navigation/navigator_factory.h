// Builds a navigator for a method (`navigation.method` in scenario files):
// gauss_newton_subgoal, potential_field or dwa.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "trackbed/navigation/dynamic_window.h"
#include "trackbed/navigation/gauss_newton_controller.h"
#include "trackbed/navigation/navigation_setup.h"
#include "trackbed/navigation/navigator.h"
#include "trackbed/navigation/potential_field.h"
#include "trackbed/navigation/progress_checker.h"
#include "trackbed/navigation/subgoal_planner.h"

namespace trackbed::navigation {

/// The point-to-point methods.
enum class NavigationMethod {
  kGaussNewtonSubgoal,  ///< Jung & Kim 2014: Gauss–Newton control with sub-goals.
  kPotentialField,      ///< Ge & Cui 2000's corrected potential field.
  kDwa,                 ///< Fox, Burgard & Thrun 1997's dynamic window.
};

/// The method's name: "gauss_newton_subgoal", "potential_field", "dwa" (what
/// Navigator::method() returns and scenario files write).
const char* ToString(NavigationMethod method);

/// Every method, in a fixed order.
const std::vector<NavigationMethod>& NavigationMethods();
/// Their names (ToString), in the same order.
const std::vector<std::string>& NavigationMethodNames();

/// Options of every method; each navigator reads the sections it needs.
struct NavigatorOptions {
  NavigationSetup setup;                  ///< Robot, control period, stop tolerances.
  ProgressCheckerOptions progress;        ///< When a run without progress ends (kStalled).
  GaussNewtonOptions gauss_newton;        ///< "gauss_newton_subgoal": the controller …
  SubgoalOptions subgoal;                 ///< … and its sub-goal switcher.
  PotentialFieldOptions potential_field;  ///< "potential_field".
  DynamicWindowOptions dwa;               ///< "dwa".

  /// Throws OptionError naming the first invalid field as its key (Serialize): the
  /// setup's and the progress checker's fields plain, the methods' as `dwa.…` etc.
  void Validate() const;

  /// The scenario file's keys for these fields (docs/scenario_format.md, `navigation`),
  /// read and written by the config archive (trackbed/common/archive.h): the setup's and
  /// the progress checker's keys at this level, each method's options in a section of
  /// its own.
  template <class Archive>
  void Serialize(Archive* a) {
    setup.Serialize(a);
    progress.Serialize(a);
    a->Visit("gauss_newton", &gauss_newton);
    a->Visit("subgoal", &subgoal);
    a->Visit("potential_field", &potential_field);
    a->Visit("dwa", &dwa);
  }
};

/// A navigator for `method` driving to `goal`. Throws OptionError for invalid options.
std::unique_ptr<Navigator> MakeNavigator(NavigationMethod method, const NavigatorOptions& options,
                                         const Pose2& goal);

/// A navigator for the method named `method` (ToString). Throws std::invalid_argument
/// naming the method and the accepted names for an unknown one, OptionError for invalid
/// options.
std::unique_ptr<Navigator> MakeNavigator(const std::string& method, const NavigatorOptions& options,
                                         const Pose2& goal);

}  // namespace trackbed::navigation
