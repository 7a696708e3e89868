#include <ritr/terms/contact_barrier_term.h>
#include <ritr/terms/friction_term.h>

#include <algorithm>
#include <stdexcept>

namespace ritr
{
  template <int dim>
  FrictionTerm<dim>::FrictionTerm(const CollisionMesh<dim> &collisions, const double coefficient,
                                  const double epsilon_v_times_h)
    : collisions_(collisions)
    , coefficient_(coefficient)
    , epsilon_v_times_h_(epsilon_v_times_h)
  {
    const auto                             &mesh = collisions_.mesh();
    std::vector<std::vector<unsigned int>> cells_of(mesh.n_nodes());
    for (unsigned int o = 0; o < mesh.n_cells(); ++o)
      for (const unsigned int n : mesh.cells[o])
        cells_of[n].push_back(o);
    boundary_cells_.assign(mesh.n_nodes(), {});
    for (const auto &facet : mesh.boundary_facets)
      for (const unsigned int o : cells_of[facet[0]])
        {
          const auto &cell = mesh.cells[o];
          if (!std::all_of(facet.begin(), facet.end(),
                           [&](const unsigned int n) { return std::find(cell.begin(), cell.end(), n) != cell.end(); }))
            continue;
          for (const unsigned int n : facet)
            if (std::find(boundary_cells_[n].begin(), boundary_cells_[n].end(), o) == boundary_cells_[n].end())
              boundary_cells_[n].push_back(o);
        }
    // A node on no boundary facet (a rod's interior node, 1D has no friction anyway) takes
    // the cells around it.
    for (unsigned int n = 0; n < mesh.n_nodes(); ++n)
      if (boundary_cells_[n].empty())
        boundary_cells_[n] = cells_of[n];
  }

  template <int dim>
  void FrictionTerm<dim>::begin_step(const StepContext<dim> &context)
  {
    u_start_        = context.u_start;
    z_start_        = context.z_start;
    old_mesh_built_ = false;
    friction_.clear();
    sources_.clear();
    unit_force_.clear();
    stencil_vertices_.clear();
    origin_gradients_.clear();
    start_ = collisions_.vertices(z_start_);
  }

  template <int dim>
  void FrictionTerm<dim>::lag(const Eigen::VectorXd &z_lagged, const CollisionCandidates &candidates, const double kappa)
  {
    if (u_start_.size() == 0)
      throw std::logic_error("FrictionTerm::lag before begin_step: the slip has no start-of-step state");
    friction_.clear();
    sources_.clear();
    unit_force_.clear();
    stencil_vertices_.clear();
    if (coefficient_ <= 0 || dim == 1)
      return;
    const Eigen::MatrixXd V = collisions_.vertices(z_lagged);
    // One constraint at a time, so that each friction term keeps its weight's sources.
    for (const auto &c : collisions_.active_constraints(V, candidates))
      for (const auto &f : contact::build_friction_constraints<dim>({c}, V, collisions_.dhat(), kappa,
                                                                    collisions_.weights(), coefficient_))
        {
          friction_.push_back(f);
          sources_.push_back(collisions_.weight_sources(c));
          unit_force_.push_back(f.normal_force / collisions_.weights().weight(c));
          for (int s = 0; s < f.n_vertices; ++s)
            if (static_cast<unsigned int>(collisions_.state_vertex(f.vertices[s])) < boundary_cells_.size())
              stencil_vertices_.push_back(f.vertices[s]);
        }
    std::sort(stencil_vertices_.begin(), stencil_vertices_.end());
    stencil_vertices_.erase(std::unique(stencil_vertices_.begin(), stencil_vertices_.end()), stencil_vertices_.end());
    update_start(collisions_.reference());
  }

  template <int dim>
  void FrictionTerm<dim>::update_start(const Eigen::VectorXd &u)
  {
    origin_gradients_.resize(stencil_vertices_.size());
    for (std::size_t k = 0; k < stencil_vertices_.size(); ++k)
      {
        const int      c = stencil_vertices_[k];
        const int      n = collisions_.state_vertex(c);
        const Vec<dim> X = u.template segment<dim>(n * dim);
        if (X == u_start_.template segment<dim>(n * dim))
          {
            // Unmoved: the node's own start position (no round-off from a barycentric sum),
            // and, on the kink, the mean slope of the boundary cells around it.
            start_.row(c)        = z_start_.template segment<dim>(n * dim).transpose();
            origin_gradients_[k] = Jacobian::Zero();
            for (const unsigned int o : boundary_cells_[n])
              origin_gradients_[k] += start_gradient(o);
            origin_gradients_[k] /= boundary_cells_[n].size();
            continue;
          }
        if (!old_mesh_built_)
          {
            old_mesh_       = transfer::OldMeshLocator<dim>(collisions_.mesh().cells, u_start_);
            old_mesh_built_ = true;
          }
        // Outside the old domain (a node sliding off a curved boundary) the nearest old
        // cell's linear extension, as the transfer has it.
        const auto location  = old_mesh_.locate(X);
        origin_gradients_[k] = start_gradient(location.cell);
        Vec<dim> origin      = Vec<dim>::Zero();
        for (int b = 0; b <= dim; ++b)
          origin += location.barycentric[b] *
                    z_start_.template segment<dim>(collisions_.mesh().cells[location.cell][b] * dim);
        start_.row(c) = origin.transpose();
      }
  }

  template <int dim>
  typename FrictionTerm<dim>::Jacobian FrictionTerm<dim>::start_gradient(const unsigned int o) const
  {
    const auto &cell = collisions_.mesh().cells[o];
    Jacobian    reference_edges, deformed_edges;
    for (int a = 0; a < dim; ++a)
      {
        reference_edges.col(a) =
          u_start_.template segment<dim>(cell[a + 1] * dim) - u_start_.template segment<dim>(cell[0] * dim);
        deformed_edges.col(a) =
          z_start_.template segment<dim>(cell[a + 1] * dim) - z_start_.template segment<dim>(cell[0] * dim);
      }
    return deformed_edges * reference_edges.inverse();
  }

  template <int dim>
  void FrictionTerm<dim>::set_reference(const Eigen::VectorXd &u)
  {
    // The collision mesh's reference (set first by the sum) holds the new weights.
    for (std::size_t j = 0; j < friction_.size(); ++j)
      if (!sources_[j].empty())
        friction_[j].normal_force = unit_force_[j] * collisions_.weight_of(sources_[j]);
    if (!friction_.empty())
      update_start(u);
  }

  template <int dim>
  double FrictionTerm<dim>::value(const TermPoint &p) const
  {
    if (friction_.empty())
      return 0.0;
    return contact::friction_energy<dim>(friction_, collisions_.vertices(p.z), start_, epsilon_v_times_h_);
  }

  template <int dim>
  void FrictionTerm<dim>::add_gradient(const TermPoint &p, Eigen::VectorXd &g) const
  {
    if (friction_.empty())
      return;
    collisions_.scatter_gradient(
      contact::friction_gradient<dim>(friction_, collisions_.vertices(p.z), start_, epsilon_v_times_h_), 1.0, g);
  }

  template <int dim>
  void FrictionTerm<dim>::add_hessian(const TermPoint &p, const bool project, MatrixAssembly<dim> &h) const
  {
    if (friction_.empty())
      return;
    collisions_.scatter_hessian(
      contact::friction_hessian<dim>(friction_, collisions_.vertices(p.z), start_, epsilon_v_times_h_, project), 1.0,
      h.triplets());
  }

  template <int dim>
  void FrictionTerm<dim>::add_hessian_and_projection(const TermPoint &p, MatrixAssembly<dim> &h) const
  {
    if (friction_.empty())
      return;
    const auto [exact, projected] =
      contact::friction_hessian_and_projection<dim>(friction_, collisions_.vertices(p.z), start_, epsilon_v_times_h_);
    const std::size_t first = h.triplets().size();
    collisions_.scatter_hessian(exact, 1.0, h.triplets());  // one triplet per stencil entry, in order
    h.change_triplets(first, exact, projected, 1.0);
  }

  template <int dim>
  void FrictionTerm<dim>::add_reference_derivatives(const TermPoint &p, const ReferenceBlock block, const bool coupling,
                                                    ReferenceDerivativeAssembly<dim> &d) const
  {
    if (friction_.empty())
      return;
    // D = sum_j w_j(u) Dhat_j(V - S(u)), with the lagged normal force per unit weight in
    // Dhat_j and the slip origins S: a body vertex's origin phi_t(u_i) moves with u_i by the
    // old cell's deformation gradient J_i, so dS/du is J_i on the vertex's own node and
    // D's u-derivatives take -J^T of its V-derivatives (S enters as -V does).
    const Eigen::MatrixXd V = collisions_.vertices(p.z);
    std::vector<int> origin_index(collisions_.n_collision_vertices(), -1);
    for (std::size_t k = 0; k < stencil_vertices_.size(); ++k)
      origin_index[stencil_vertices_[k]] = k;
    const std::vector<Jacobian> &J = origin_gradients_;
    Triplets &huu = d.huu.triplets();
    Triplets  hxu;
    for (std::size_t j = 0; j < friction_.size(); ++j)
      {
        auto unit         = friction_[j];
        unit.normal_force = unit_force_[j];
        const double weight = unit_force_[j] != 0 ? friction_[j].normal_force / unit_force_[j] : 0.0;
        const std::vector<contact::FrictionConstraint<dim>> one{unit};
        const double          energy = contact::friction_energy<dim>(one, V, start_, epsilon_v_times_h_);
        const Eigen::VectorXd full   = contact::friction_gradient<dim>(one, V, start_, epsilon_v_times_h_);
        const int             n      = unit.n_vertices;
        std::vector<int>      stencil(unit.vertices.begin(), unit.vertices.begin() + n);
        Eigen::VectorXd       gradient(n * dim);
        for (int s = 0; s < n; ++s)
          gradient.segment<dim>(s * dim) = full.segment<dim>(stencil[s] * dim);
        collisions_.add_weight_derivatives(sources_[j], energy, stencil, gradient, d.gu, huu, hxu);

        // Stencil Hessian of Dhat_j in V: the projected one, which equals the exact one (the
        // tangential matrix is PSD analytically; the projection clips round-off only).
        Eigen::MatrixXd hessian = Eigen::MatrixXd::Zero(n * dim, n * dim);
        const auto      position = [&](const int row) {
          const int c = row / dim;
          return static_cast<int>(std::find(stencil.begin(), stencil.end(), c) - stencil.begin()) * dim + row % dim;
        };
        for (const auto &t : contact::friction_hessian<dim>(one, V, start_, epsilon_v_times_h_, true))
          hessian(position(t.row()), position(t.col())) += t.value();
        const auto dw = collisions_.weight_gradient(sources_[j]);
        for (int t = 0; t < n; ++t)
          {
            const int k = origin_index[stencil[t]];
            if (k < 0)
              continue;  // an obstacle vertex: its origin is scripted
            const unsigned int node = collisions_.state_vertex(stencil[t]);
            // dDhat/du_t = -J_t^T dDhat/dV_t: with the weight into g_u, and against dw/du
            // into H_uu both ways.
            const Vec<dim> a = -J[k].transpose() * gradient.segment<dim>(t * dim);
            for (int l = 0; l < dim; ++l)
              {
                d.gu[node * dim + l] += weight * a[l];
                for (const auto &[ui, dwi] : dw)
                  {
                    huu.emplace_back(node * dim + l, ui, a[l] * dwi);
                    huu.emplace_back(ui, node * dim + l, a[l] * dwi);
                  }
              }
            for (int s = 0; s < n; ++s)
              {
                // d2/dV_s du_t = -w H_st J_t; d2/du_s du_t = w J_s^T H_st J_t.
                const Jacobian mixed = -weight * hessian.block<dim, dim>(s * dim, t * dim) * J[k];
                const int      ks    = origin_index[stencil[s]];
                const int      row   = collisions_.state_vertex(stencil[s]);  // a node if ks >= 0
                for (int a1 = 0; a1 < dim; ++a1)
                  for (int b1 = 0; b1 < dim; ++b1)
                    hxu.emplace_back(row * dim + a1, node * dim + b1, mixed(a1, b1));
                if (ks < 0)
                  continue;
                const Jacobian both = -J[ks].transpose() * mixed;
                for (int a1 = 0; a1 < dim; ++a1)
                  for (int b1 = 0; b1 < dim; ++b1)
                    huu.emplace_back(row * dim + a1, node * dim + b1, both(a1, b1));
              }
          }
      }
    if (block != ReferenceBlock::following && !coupling)
      return;
    Triplets hessian;
    collisions_.scatter_hessian(contact::friction_hessian<dim>(friction_, V, start_, epsilon_v_times_h_, true), 1.0,
                                hessian);
    add_contact_state_blocks(p.u.size(), hessian, hxu, block, coupling, d.huu.triplets(), d.hxx.triplets(),
                             d.hxu.triplets());
    if (coupling)
      collisions_.scatter_gradient(contact::friction_gradient<dim>(friction_, V, start_, epsilon_v_times_h_), 1.0, d.gx);
  }

  template class FrictionTerm<1>;
  template class FrictionTerm<2>;
  template class FrictionTerm<3>;
} // namespace ritr
