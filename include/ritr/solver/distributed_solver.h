#pragma once
#include <ritr/common/enum_names.h>

namespace ritr
{
  // How a run shared among processes solves its Newton systems (distributed_linear_system.h).
  enum class DistributedSolver
  {
    direct,  // Amesos with MUMPS: a distributed sparse LU
    amg      // conjugate gradients preconditioned by ML's algebraic multigrid
  };

  // Their names in a parameter file (Solver/distributed solver).
  inline constexpr EnumNames<DistributedSolver, 2> distributed_solver_names{
    {{DistributedSolver::direct, "direct"}, {DistributedSolver::amg, "amg"}}};
} // namespace ritr
