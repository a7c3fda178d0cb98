// Navigator factory (see navigator_factory.h).
#include "trackbed/navigation/navigator_factory.h"

#include <stdexcept>

#include "trackbed/common/option_error.h"
#include "trackbed/navigation/gauss_newton_subgoal_navigator.h"

namespace trackbed::navigation {

void NavigatorOptions::Validate() const {
  option_check::Nested("setup", setup);
  option_check::Nested("progress", progress);
  option_check::Nested("gauss_newton", gauss_newton);
  option_check::Nested("subgoal", subgoal);
  option_check::Nested("potential_field", potential_field);
  option_check::Nested("dwa", dwa);
}

const std::vector<std::string>& NavigationMethodNames() {
  static const std::vector<std::string> names = {"gauss_newton_subgoal", "potential_field", "dwa"};
  return names;
}

std::unique_ptr<Navigator> MakeNavigator(const std::string& method, const NavigatorOptions& options,
                                         const Pose2& goal) {
  if (method == "gauss_newton_subgoal") {
    return std::make_unique<GaussNewtonSubgoalNavigator>(options.setup, options.gauss_newton,
                                                         options.subgoal, options.progress, goal);
  }
  if (method == "potential_field") {
    return std::make_unique<PotentialFieldNavigator>(options.setup, options.potential_field,
                                                     options.progress, goal);
  }
  if (method == "dwa") {
    return std::make_unique<DynamicWindowNavigator>(options.setup, options.dwa, options.progress,
                                                    goal);
  }
  throw std::invalid_argument("MakeNavigator: unknown navigation method '" + method +
                              "' (expected gauss_newton_subgoal, potential_field or dwa)");
}

}  // namespace trackbed::navigation
