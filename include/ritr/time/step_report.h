#pragma once
// What one step did: a row of log.csv, a line of progress, and (kept for every step) the
// totals of summary.json. Checkpoints store it too, so that a resumed run reports the steps
// it did not redo.
#include <ritr/adaptivity/outer_stop.h>

#include <limits>
#include <optional>

namespace ritr
{
  struct StepReport
  {
    unsigned int step = 0;
    double       time = 0;
    double       energy = 0;
    unsigned int newton_iterations = 0;
    unsigned int outer_iterations  = 0;
    unsigned int line_search_trials = 0;
    // r-adaptivity: R at the step's start mesh (the step never ends above it), the boundary
    // sliding violation and the time split between inner solves, transfer and outer solves.
    double       initial_objective = 0;
    double       sliding_violation = 0;
    double       inner_seconds = 0, transfer_seconds = 0, outer_solve_seconds = 0;
    double       min_distance = std::numeric_limits<double>::infinity();
    double       min_reference_measure = 0;
    double       min_deformed_jacobian = 0;
    double       wall_seconds = 0;
    std::optional<OuterStop> outer_stop;  // r-adaptivity only
  };
} // namespace ritr
