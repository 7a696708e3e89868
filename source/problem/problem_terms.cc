// Which terms a scene's steps minimise, in the order they are summed: elasticity first, so
// that the inertia adds its mass blocks to the elastic cell blocks as one kernel would.
#include <ritr/adaptivity/ritr_options.h>
#include <ritr/common/input_error.h>
#include <ritr/mesh/simplex_rules.h>
#include <ritr/problem/problem.h>
#include <ritr/terms/body_force_term.h>
#include <ritr/terms/contact_barrier_term.h>
#include <ritr/terms/elasticity_term.h>
#include <ritr/terms/friction_term.h>
#include <ritr/terms/measure_barrier_term.h>
#include <ritr/terms/transferred_inertia_term.h>

namespace ritr
{
  template <int dim>
  SimplexQuadrature<dim> Problem<dim>::transfer_quadrature() const
  {
    // Witherden-Vincent rules as in the paper, which integrate the transfer's piecewise
    // integrand (kinks inside candidate cells) far better than low-order rules. A rod's cells
    // are cheap, so there the rule is repeated on sub-cells by default.
    const unsigned int subdivisions = scene.adaptivity.quadrature_subdivisions > 0 ?
                                        scene.adaptivity.quadrature_subdivisions :
                                        (dim == 1 ? 64 : 1);
    return composite_rule(witherden_vincent_rule<dim>(5), subdivisions);
  }

  template <int dim>
  transfer::TransferIntegration Problem<dim>::transfer_integration() const
  {
    switch (scene.adaptivity.transfer_integration)
      {
        case TransferIntegrationChoice::exact:
          if (dim != 2)
            throw InputError(scene.where("Adaptivity/transfer integration") +
                             ": exact is implemented for triangles (2D) only");
          return transfer::TransferIntegration::exact;
        case TransferIntegrationChoice::quadrature:
          return transfer::TransferIntegration::quadrature;
        case TransferIntegrationChoice::automatic:
        default:
          return dim == 2 ? transfer::TransferIntegration::exact : transfer::TransferIntegration::quadrature;
      }
  }

  template <int dim>
  void Problem<dim>::share_cells()
  {
    if (!work_share.distributed())
      return;
    if (scene.adaptivity.enabled)
      throw InputError(scene.where("Adaptivity/enabled") + ": r-adaptivity runs without mpirun (fixed meshes only are shared among processes)");
    work_share.partition(mesh.cells, mesh.n_nodes());
    owned_mesh.reference = mesh.reference;
    owned_mesh.node_body = mesh.node_body;
    owned_mesh.node_part = mesh.node_part;
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      if (work_share.owns_cell(c))
        {
          owned_mesh.cells.push_back(mesh.cells[c]);
          owned_mesh.cell_material.push_back(mesh.cell_material[c]);
        }
    owned_materials = std::make_unique<CellMaterials<dim>>(owned_mesh, scene.materials);
  }

  template <int dim>
  void Problem<dim>::build_terms()
  {
    const AdaptivityScene &adaptivity = scene.adaptivity;
    // The cell terms sum over this process's cells; the contact terms see this process's
    // candidates (TermSum::share_work).
    const CellMaterials<dim> &cell_materials = owned_materials ? *owned_materials : *materials;
    terms = std::make_unique<TermSum<dim>>(cell_materials.mesh(), collisions.get());
    terms->share_work(work_share);
    terms->template add<ElasticityTerm<dim>>(cell_materials);
    if (scene.dynamic())
      {
        if (adaptivity.enabled && adaptivity.projection == PredictorProjection::in_optimization)
          try
            {
              terms->template add<TransferredInertiaTerm<dim>>(*materials, transfer_quadrature(), adaptivity.inertia,
                                                               transfer_integration());
            }
          catch (const std::invalid_argument &e)
            {
              throw InputError(scene.where("Adaptivity/enabled") + ": " + e.what());
            }
        else
          // A fixed mesh reads the predictor's nodal values on its own mesh; r-ITR projecting
          // after the optimisation does so on every candidate mesh (the ablation of Fig. 6).
          terms->template add<InertiaTerm<dim>>(cell_materials, InertiaTerm<dim>::Predictor::nodal,
                                                adaptivity.enabled ? adaptivity.inertia : InertiaForm::corrected);
      }
    terms->template add<BodyForceTerm<dim>>(cell_materials);
    if (collisions)
      {
        terms->template add<ContactBarrierTerm<dim>>(*collisions);
        if (scene.contact.friction_coefficient > 0)
          terms->template add<FrictionTerm<dim>>(*collisions, scene.contact.friction_coefficient,
                                                 scene.contact.epsilon_v * scene.time_step);
      }
    if (adaptivity.enabled)
      terms->template add<MeasureBarrierTerm<dim>>(mesh);
  }

#define RITR_INSTANTIATE(dim)                                                                                          \
  template SimplexQuadrature<dim> Problem<dim>::transfer_quadrature() const;                                           \
  template transfer::TransferIntegration Problem<dim>::transfer_integration() const;                                   \
  template void                   Problem<dim>::build_terms();                                                         \
  template void                   Problem<dim>::share_cells();
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr
