#pragma once
// An r-ITR step solver on a mesh without contact, assembled the way the simulation does it:
// bulk terms, the implicit step on a given mesh, and the outer solver around it.
#include <ritr/adaptivity/ritr_solver.h>

#include <memory>

namespace ritr::test_support
{
  template <int dim>
  struct RitrSetup
  {
    // `kinematic` marks prescribed state entries (empty: none).
    RitrSetup(const SimplexMesh<dim> &m, const Material &material, const RitrSettings &settings,
              const SimplexQuadrature<dim> &quadrature, std::vector<bool> kinematic = {},
              const double inner_tolerance = 1e-10)
      : mesh(m)
      , bulk(mesh, std::vector<Material>(
                     *std::max_element(mesh.cell_material.begin(), mesh.cell_material.end()) + 1, material))
    {
      if (kinematic.empty())
        kinematic.assign(mesh.reference.size(), false);
      ImplicitStepSettings step_settings;
      step_settings.newton.tolerance = inner_tolerance;
      inner  = std::make_unique<ImplicitStep<dim>>(bulk, nullptr, kinematic, step_settings);
      solver = std::make_unique<RitrSolver<dim>>(mesh, bulk, nullptr, *inner, settings, quadrature);
    }

    SimplexMesh<dim>                   mesh;
    BulkEnergy<dim>                    bulk;
    std::unique_ptr<ImplicitStep<dim>> inner;
    std::unique_ptr<RitrSolver<dim>>   solver;
  };
} // namespace ritr::test_support
