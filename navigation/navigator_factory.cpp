// Navigator factory (see navigator_factory.h).
#include "trackbed/navigation/navigator_factory.h"

#include <stdexcept>

#include "trackbed/common/option_error.h"
#include "trackbed/navigation/gauss_newton_subgoal_navigator.h"

namespace trackbed::navigation {

void NavigatorOptions::Validate() const {
  setup.Validate();
  progress.Validate();
  option_check::Nested("gauss_newton", gauss_newton);
  option_check::Nested("subgoal", subgoal);
  option_check::Nested("potential_field", potential_field);
  option_check::Nested("dwa", dwa);
}

const char* ToString(NavigationMethod method) {
  switch (method) {
    case NavigationMethod::kGaussNewtonSubgoal:
      return "gauss_newton_subgoal";
    case NavigationMethod::kPotentialField:
      return "potential_field";
    case NavigationMethod::kDwa:
      return "dwa";
  }
  return "unknown";
}

const std::vector<NavigationMethod>& NavigationMethods() {
  static const std::vector<NavigationMethod> methods = {NavigationMethod::kGaussNewtonSubgoal,
                                                        NavigationMethod::kPotentialField,
                                                        NavigationMethod::kDwa};
  return methods;
}

const std::vector<std::string>& NavigationMethodNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (NavigationMethod m : NavigationMethods()) n.emplace_back(ToString(m));
    return n;
  }();
  return names;
}

std::unique_ptr<Navigator> MakeNavigator(NavigationMethod method, const NavigatorOptions& options,
                                         const Pose2& goal) {
  switch (method) {
    case NavigationMethod::kGaussNewtonSubgoal:
      return std::make_unique<GaussNewtonSubgoalNavigator>(options.setup, options.gauss_newton,
                                                           options.subgoal, options.progress, goal);
    case NavigationMethod::kPotentialField:
      return std::make_unique<PotentialFieldNavigator>(options.setup, options.potential_field,
                                                       options.progress, goal);
    case NavigationMethod::kDwa:
      return std::make_unique<DynamicWindowNavigator>(options.setup, options.dwa, options.progress,
                                                      goal);
  }
  throw std::invalid_argument("MakeNavigator: unknown navigation method");
}

std::unique_ptr<Navigator> MakeNavigator(const std::string& method, const NavigatorOptions& options,
                                         const Pose2& goal) {
  for (NavigationMethod m : NavigationMethods()) {
    if (method == ToString(m)) return MakeNavigator(m, options, goal);
  }
  throw std::invalid_argument("MakeNavigator: unknown navigation method '" + method +
                              "' (expected gauss_newton_subgoal, potential_field or dwa)");
}

}  // namespace trackbed::navigation
