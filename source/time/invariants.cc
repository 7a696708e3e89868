#include <ritr/metrics/mesh_metrics.h>
#include <ritr/time/invariants.h>

#include <algorithm>
#include <cmath>

namespace ritr
{
  template <int dim>
  InvariantChecker<dim>::InvariantChecker(const SimplexMesh<dim> &mesh, const CollisionMesh<dim> *collisions,
                                          const std::vector<bool>         &kinematic,
                                          const std::vector<std::pair<unsigned int, unsigned int>> &sliding_dirichlet_nodes)
    : mesh_(mesh)
    , collisions_(collisions)
    , kinematic_(kinematic)
  {
    for (const auto &[n, condition] : sliding_dirichlet_nodes)
      for (int k = 0; k < dim; ++k)
        sliding_entries_.push_back(n * dim + k);
  }

  template <int dim>
  std::vector<std::string> InvariantChecker<dim>::check(StepResult &result, const Eigen::VectorXd &targets) const
  {
    StepReport              &report = result.report;
    const std::string        step   = "step " + std::to_string(report.step) + ": ";
    std::vector<std::string> violations;
    if (report.outer_stop)
      {
        if (!(report.energy <= report.initial_objective))
          violations.push_back(step + "R above its start-of-step value");
        if (!(report.sliding_violation <= 1e-8))
          violations.push_back(step + "boundary sliding violation " + std::to_string(report.sliding_violation));
      }
    const Eigen::VectorXd x = result.z.head(result.u.size());
    if (collisions_)
      report.min_distance = collisions_->minimum_distance(result.z);
    report.min_reference_measure = min_cell_measure(mesh_, result.u, false);
    report.min_deformed_jacobian = min_deformed_jacobian(mesh_, x, result.u);
    if (!(report.min_distance > 0))
      violations.push_back(step + "minimum distance " + std::to_string(report.min_distance));
    if (!(report.min_reference_measure > 0))
      violations.push_back(step + "inverted reference element");
    if (!(report.min_deformed_jacobian > 0))
      violations.push_back(step + "inverted element (det F = " + std::to_string(report.min_deformed_jacobian) + ")");
    const Eigen::VectorXd expected = sliding_dirichlet_targets(targets, result.u, mesh_.reference, sliding_entries_);
    double                off      = 0;
    for (std::size_t e = 0; e < kinematic_.size(); ++e)
      if (kinematic_[e])
        off = std::max(off, std::abs(result.z[e] - expected[e]) / (1 + std::abs(expected[e])));
    if (!(off <= 1e-9))
      violations.push_back(step + "prescribed entry off its target by " + std::to_string(off));
    return violations;
  }

  template class InvariantChecker<1>;
  template class InvariantChecker<2>;
  template class InvariantChecker<3>;
} // namespace ritr
