#pragma once
// Why the outer iteration of an r-ITR step stopped: a column of log.csv and a count in
// summary.json, so that a step that ran out of iterations is never read as converged.
#include <ritr/common/enum_names.h>

namespace ritr
{
  enum class OuterStop
  {
    converged,        // the Newton step fell below epsilon_r (or R cannot resolve it)
    small_decrease,   // the predicted decrease fell below the decrease tolerance
    no_decrease,      // no trial (line search or trust region) kept R from increasing
    iteration_limit   // max_outer_iterations reached
  };

  inline constexpr EnumNames<OuterStop, 4> outer_stop_names{{{OuterStop::converged, "converged"},
                                                             {OuterStop::small_decrease, "small_decrease"},
                                                             {OuterStop::no_decrease, "no_decrease"},
                                                             {OuterStop::iteration_limit, "iteration_limit"}}};
} // namespace ritr
