#include <ritr/common/wall_clock.h>
#include <ritr/mesh/obstacle_reader.h>
#include <ritr/mesh/simplex_rules.h>
#include <ritr/metrics/mesh_metrics.h>
#include <ritr/scene/parameters.h>
#include <ritr/time/simulation.h>

#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

namespace ritr
{
  namespace
  {
    template <int dim>
    Vec<dim> to_vec(const std::vector<double> &v)
    {
      Vec<dim> r;
      for (int k = 0; k < dim; ++k)
        r[k] = v[k];
      return r;
    }

    // The .prm subsection of the i-th enabled body, condition or obstacle.
    std::string section(const std::string &name, const std::string &kind, const std::size_t i)
    {
      return name.empty() ? kind + " " + std::to_string(i) : name;
    }

    // Expressions are evaluated where they are first used (initial nodes, t = 0 and the first
    // step's time) before anything runs, so that NaN or inf is bad input, not a failed step.
    template <int dim>
    Eigen::VectorXd finite_value(const Expression<dim> &expression, const Vec<dim> &x, const double t,
                                 const std::string &where)
    {
      const Eigen::VectorXd v = expression.vector_value(x, t);
      if (!v.allFinite())
        {
          std::ostringstream s;
          s << where << ": is not finite at x = ("
            << x.transpose().format(Eigen::IOFormat(Eigen::StreamPrecision, Eigen::DontAlignCols, ", ", ", "))
            << "), t = " << t;
          throw InputError(s.str());
        }
      return v;
    }
  } // namespace

  template <int dim>
  Simulation<dim>::~Simulation() = default;

  template <int dim>
  Simulation<dim>::Simulation(const Scene &scene)
    : scene_(scene)
  {
    std::vector<BodyDescription> bodies;
    for (const auto &b : scene.bodies)
      bodies.push_back(b.geometry);
    try
      {
        mesh_ = build_mesh<dim>(bodies);
        bulk_ = std::make_unique<BulkEnergy<dim>>(mesh_, scene.materials);
      }
    catch (const InputError &)
      {
        throw;
      }
    catch (const std::exception &e)
      {
        // Name the body: only now, rebuild the bodies one at a time to find the one at fault.
        std::string name = "Body";
        for (std::size_t b = 0; b < bodies.size() && name == "Body"; ++b)
          try
            {
              build_mesh<dim>({bodies[b]});
            }
          catch (const std::exception &)
            {
              name = section(scene.bodies[b].section, "Body", b);
            }
        throw InputError(scene.where(name) + ": " + e.what());
      }
    u_ = mesh_.reference;
    x_ = u_;
    v_ = Eigen::VectorXd::Zero(u_.size());
    std::vector<Expression<dim>> velocity;
    std::vector<std::string>     velocity_entry;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
      {
        velocity.emplace_back(scene.bodies[b].initial_velocity, dim);
        velocity_entry.push_back(scene.where(section(scene.bodies[b].section, "Body", b) + "/initial velocity"));
      }
    for (unsigned int i = 0; i < mesh_.n_nodes(); ++i)
      {
        const unsigned int b              = mesh_.node_part[i];
        v_.template segment<dim>(i * dim) = finite_value(velocity[b], mesh_.reference_node(i), 0.0, velocity_entry[b]);
      }
    load_factor_.emplace(scene.load_factor, 1);
    for (const double t : {0.0, scene.time_step})
      finite_value<dim>(*load_factor_, Vec<dim>::Zero(), t, scene.where("Gravity/load factor"));

    setup_obstacles();
    setup_dirichlet();
    if (scene.contact.enabled)
      {
        ContactSettings settings;
        settings.dhat                 = scene.contact.dhat;
        settings.friction_coefficient = scene.contact.friction_coefficient;
        settings.epsilon_v_times_h    = scene.contact.epsilon_v * scene.time_step;
        settings.self_contact         = scene.contact.self_contact;
        contact_ = std::make_unique<ContactPotential<dim>>(mesh_, obstacles_, settings);
      }
    ImplicitStepSettings step_settings;
    step_settings.newton.max_iterations = scene.solver.max_iterations;
    step_settings.newton.tolerance =
      scene.dynamic() ? scene.solver.newton_tolerance * scene.time_step :
                        scene.solver.static_tolerance * (contact_ ? contact_->bbox_diagonal(state()) : 1.0);
    step_settings.friction_iterations =
      contact_ && scene.contact.friction_coefficient > 0 ? scene.contact.friction_iterations : 1;
    step_settings.barrier_stiffness = scene.contact.barrier_stiffness;
    step_settings.dhat              = scene.contact.dhat;
    if (scene.solver.newton_log)
      step_settings.newton.monitor = [this](const NewtonIterationRecord &record, const Eigen::VectorXd &z) {
        log_newton_iteration(record, z);
      };
    implicit_step_ = std::make_unique<ImplicitStep<dim>>(*bulk_, contact_.get(), kinematic_, step_settings);
    if (scene.adaptivity.enabled)
      setup_adaptivity();
    check_initial_state();
  }

  template <int dim>
  void Simulation<dim>::setup_adaptivity()
  {
    const AdaptivityScene &a = scene_.adaptivity;
    RitrSettings           settings;
    settings.hessian    = a.hessian == "full" ? RitrHessian::full :
                          a.hessian == "filtered" ? RitrHessian::filtered : RitrHessian::truncated;
    settings.inertia    = a.inertia == "uncorrected" ? InertiaForm::uncorrected : InertiaForm::corrected;
    settings.projection = a.projection == "after-optimization" ? PredictorProjection::after_optimization :
                                                                 PredictorProjection::in_optimization;
    settings.geometric_admissibility = a.admissibility == "geometric" || a.admissibility == "both";
    settings.physical_admissibility  = a.admissibility == "physical" || a.admissibility == "both";
    settings.sliding_tolerance       = a.sliding_tolerance;
    settings.max_outer_iterations    = a.max_iterations;
    settings.measure_barrier_stiffness = a.measure_barrier_stiffness;
    // epsilon_r is given relative to the bounding-box diagonal of the reference domain.
    double diagonal2 = 0;
    for (int k = 0; k < dim; ++k)
      {
        const auto coordinates =
          Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<dim>>(u_.data() + k, mesh_.n_nodes());
        diagonal2 += std::pow(coordinates.maxCoeff() - coordinates.minCoeff(), 2);
      }
    settings.epsilon_r = a.epsilon_r * std::sqrt(diagonal2);
    // Witherden-Vincent rules as in the paper, which integrate the transfer's piecewise
    // integrand (kinks inside candidate cells) far better than low-order rules. A rod's cells
    // are cheap, so there the rule is repeated on sub-cells by default.
    const unsigned int subdivisions = a.quadrature_subdivisions > 0 ? a.quadrature_subdivisions : (dim == 1 ? 64 : 1);
    try
      {
        ritr_ = std::make_unique<RitrSolver<dim>>(mesh_, *bulk_, contact_.get(), *implicit_step_, settings,
                                                  transfer::composite_rule(witherden_vincent_rule<dim>(5), subdivisions));
      }
    catch (const std::invalid_argument &e)
      {
        throw InputError(scene_.where("Adaptivity/enabled") + ": " + e.what());
      }
    if (!settings.physical_admissibility && contact_)
      throw InputError(scene_.where("Adaptivity/admissibility") +
                       ": without physical admissibility contact is not supported");
  }

  template <int dim>
  void Simulation<dim>::setup_obstacles()
  {
    for (std::size_t o = 0; o < scene_.obstacles.size(); ++o)
      {
        const ObstacleScene &s    = scene_.obstacles[o];
        const std::string    name = section(s.section, "Obstacle", o);
        contact::RigidObstacle<dim> obstacle;
        try
          {
            if (s.type == "plane")
              obstacle = contact::make_plane<dim>(to_vec<dim>(s.point), to_vec<dim>(s.normal), s.size[0]);
            else if (s.type == "box" || s.type == "punch")
              obstacle = contact::make_box<dim>(to_vec<dim>(s.point), to_vec<dim>(s.size));
            else if (s.type == "spikes")
              obstacle = contact::make_spikes<dim>(to_vec<dim>(s.point), s.size[0], s.count, s.spike_height);
            else if (s.file.size() > 4 && s.file.substr(s.file.size() - 4) == ".msh")
              obstacle = read_obstacle_msh<dim>(s.file);
            else
              obstacle = contact::read_obj<dim>(s.file);
          }
        catch (const std::exception &e)
          {
            throw InputError(scene_.where(name) + ": " + e.what());
          }
        obstacle.center = to_vec<dim>(s.rotation_center);
        obstacle.axis   = Eigen::Vector3d(s.rotation_axis[0], s.rotation_axis[1], s.rotation_axis[2]);
        auto translation = std::make_shared<Expression<dim>>(s.translation, dim);
        auto angle       = std::make_shared<Expression<dim>>(s.rotation_angle, 1);
        for (const double t : {0.0, scene_.time_step})
          {
            finite_value<dim>(*translation, Vec<dim>::Zero(), t, scene_.where(name + "/translation"));
            finite_value<dim>(*angle, Vec<dim>::Zero(), t, scene_.where(name + "/rotation angle"));
          }
        obstacle.translation = [translation](double t) {
          return Vec<dim>(translation->vector_value(Vec<dim>::Zero(), t));
        };
        obstacle.angle = [angle](double t) { return angle->value(Vec<dim>::Zero(), t); };
        obstacles_.push_back(std::move(obstacle));
      }
    unsigned int n = 0;
    for (const auto &o : obstacles_)
      n += o.rest_vertices.size();
    obstacle_positions_.resize(n * dim);
    for (unsigned int i = 0, o = 0; o < obstacles_.size(); ++o)
      for (const auto &p : obstacles_[o].vertices_at(0.0))
        obstacle_positions_.template segment<dim>(dim * i++) = p;
  }

  template <int dim>
  void Simulation<dim>::setup_dirichlet()
  {
    std::vector<int> condition_of(mesh_.n_nodes(), -1);
    const auto       name = [&](const unsigned int d) { return section(scene_.dirichlet[d].section, "Dirichlet", d); };
    for (unsigned int d = 0; d < scene_.dirichlet.size(); ++d)
      {
        const DirichletScene &bc           = scene_.dirichlet[d];
        const std::string     region_entry = scene_.where(name(d) + "/region");
        const std::string     displacement_entry = scene_.where(name(d) + "/displacement");
        std::vector<bool>     selected(mesh_.n_nodes(), false);
        if (!bc.region.empty())
          {
            const Expression<dim> region(bc.region, 1);
            for (unsigned int i = 0; i < mesh_.n_nodes(); ++i)
              selected[i] = finite_value(region, mesh_.reference_node(i), 0.0, region_entry)[0] > 0;
          }
        else
          for (unsigned int f = 0; f < mesh_.boundary_facets.size(); ++f)
            if (std::find(bc.boundary_ids.begin(), bc.boundary_ids.end(), mesh_.boundary_ids[f]) !=
                bc.boundary_ids.end())
              for (const unsigned int n : mesh_.boundary_facets[f])
                selected[n] = true;
        dirichlet_displacements_.emplace_back(bc.displacement, dim);
        unsigned int count = 0;
        for (unsigned int i = 0; i < mesh_.n_nodes(); ++i)
          if (selected[i])
            {
              ++count;
              for (const double t : {0.0, scene_.time_step})
                finite_value(dirichlet_displacements_[d], mesh_.reference_node(i), t, displacement_entry);
              if (condition_of[i] >= 0)
                {
                  // Two conditions on one node must agree at all times we can check cheaply.
                  for (const double t : {0.0, 0.5 * scene_.end_time, scene_.end_time})
                    if ((dirichlet_displacements_[condition_of[i]].vector_value(mesh_.reference_node(i), t) -
                         dirichlet_displacements_[d].vector_value(mesh_.reference_node(i), t))
                          .norm() > 1e-12)
                      throw InputError(scene_.where(name(d)) + ": contradicts " + name(condition_of[i]) +
                                       " on shared nodes");
                  continue;
                }
              condition_of[i] = d;
              dirichlet_nodes_.emplace_back(i, d);
            }
        if (count == 0)
          throw InputError(scene_.where(name(d)) + ": selects no node");
      }
    kinematic_.assign(u_.size() + obstacle_positions_.size(), false);
    for (const auto &[node, condition] : dirichlet_nodes_)
      for (int k = 0; k < dim; ++k)
        kinematic_[node * dim + k] = true;
    for (Eigen::Index i = u_.size(); i < static_cast<Eigen::Index>(kinematic_.size()); ++i)
      kinematic_[i] = true;
    // Dirichlet nodes start at their prescribed position.
    const Eigen::VectorXd targets = state_targets(0.0);
    for (const auto &[node, condition] : dirichlet_nodes_)
      x_.template segment<dim>(node * dim) = targets.template segment<dim>(node * dim);
  }

  template <int dim>
  void Simulation<dim>::check_initial_state() const
  {
    const std::string &file = scene_.parameter_file;
    double             smallest = std::numeric_limits<double>::max(), largest = 0;
    for (unsigned int c = 0; c < mesh_.n_cells(); ++c)
      {
        const double m = std::abs(signed_cell_measure(c));
        smallest       = std::min(smallest, m);
        largest        = std::max(largest, m);
      }
    if (!(smallest > 1e-12 * largest))
      throw InputError(file + ": Body: the mesh has degenerate (zero-measure) elements");
    if (!(min_deformed_jacobian(mesh_, x_, u_) > 0))
      throw InputError(file + ": Dirichlet: the initial prescribed displacement inverts elements");
    if (contact_)
      {
        // Distances at round-off level are contact too: the barrier could not push them apart.
        const double d = contact_->minimum_distance(state());
        if (!(d > 1e-12 * contact_->bbox_diagonal(state())) || contact_->has_intersections(state()))
          throw InputError(file + ": the initial configuration intersects (bodies or obstacles overlap or touch)");
      }
  }

  template <int dim>
  Eigen::VectorXd Simulation<dim>::state() const
  {
    Eigen::VectorXd z(x_.size() + obstacle_positions_.size());
    z << x_, obstacle_positions_;
    return z;
  }

  template <int dim>
  Eigen::VectorXd Simulation<dim>::state_targets(const double t) const
  {
    Eigen::VectorXd z = Eigen::VectorXd::Zero(u_.size() + obstacle_positions_.size());
    for (const auto &[node, condition] : dirichlet_nodes_)
      z.template segment<dim>(node * dim) =
        mesh_.reference_node(node) + Vec<dim>(dirichlet_displacements_[condition].vector_value(mesh_.reference_node(node), t));
    unsigned int i = mesh_.n_nodes();
    for (const auto &o : obstacles_)
      for (const auto &p : o.vertices_at(t))
        z.template segment<dim>(dim * i++) = p;
    return z;
  }

  template <int dim>
  double Simulation<dim>::signed_cell_measure(const unsigned int c) const
  {
    return simplex_measure<dim, double>(cell_nodes<dim>(u_, mesh_.cells[c]));
  }

  template <int dim>
  StepReport Simulation<dim>::advance()
  {
    const auto   start   = std::chrono::steady_clock::now();
    const double h       = scene_.time_step;
    // The last step lands on the end time, not on an accumulation of rounded steps.
    const double t1      = step_ + 1 == scene_.n_steps() ? scene_.end_time : time_ + h;
    const bool   dynamic = scene_.dynamic();

    StepContext<dim> context;
    context.step      = step_ + 1;
    context.time      = t1;
    context.time_step = h;
    context.dynamic   = dynamic;
    const double load = load_factor_->value(Vec<dim>::Zero(), t1);
    for (int k = 0; k < dim; ++k)
      context.gravity[k] = scene_.gravity[k] * load;
    context.u_start = u_;
    context.z_start = state();
    context.v_start = v_;
    context.targets = state_targets(t1);
    bulk_->set_weights(context.cell_weights());
    bulk_->set_predictor(context.predictor());

    StepReport report;
    report.step = step_ + 1;
    report.time = t1;
    if (ritr_)
      {
        advance_adaptive(report, context);
        report.wall_seconds = seconds_since(start);
        history_.push_back(report);
        return report;
      }

    Eigen::VectorXd z = state();
    try
      {
        const auto r = implicit_step_->solve_start_of_step(context, z);
        report.newton_iterations  = r.iterations;
        report.line_search_trials = r.line_search_trials;
        report.energy             = r.energy;
      }
    catch (const ConvergenceError &e)
      {
        throw ConvergenceError("step " + std::to_string(step_ + 1) + " (t = " + std::to_string(t1) +
                               ") did not converge: " + e.what());
      }

    const Eigen::VectorXd x_new = z.head(x_.size());
    v_                  = dynamic ? Eigen::VectorXd((x_new - x_) / h) : Eigen::VectorXd::Zero(x_.size());
    x_                  = x_new;
    obstacle_positions_ = z.tail(obstacle_positions_.size());
    time_               = t1;
    ++step_;
    check_invariants(report);
    report.wall_seconds = seconds_since(start);
    history_.push_back(report);
    return report;
  }

  template <int dim>
  void Simulation<dim>::advance_adaptive(StepReport &report, const StepContext<dim> &context)
  {
    typename RitrSolver<dim>::Result r;
    try
      {
        r = ritr_->step(context);
      }
    catch (const ConvergenceError &e)
      {
        throw ConvergenceError("step " + std::to_string(step_ + 1) + ": " + e.what());
      }
    u_                  = r.u;
    x_                  = r.z.head(u_.size());
    obstacle_positions_ = r.z.tail(obstacle_positions_.size());
    v_                  = r.v;
    time_ = report.time;
    ++step_;
    report.energy              = r.objective;
    report.initial_objective   = r.initial_objective;
    report.sliding_violation   = r.sliding_violation;
    report.newton_iterations   = r.inner_iterations;
    report.outer_iterations    = r.outer_iterations;
    report.line_search_trials  = r.line_search_trials;
    report.inner_seconds       = r.inner_seconds;
    report.transfer_seconds    = r.transfer_seconds;
    report.outer_solve_seconds = r.outer_solve_seconds;
    const std::string step = "step " + std::to_string(step_) + ": ";
    if (!(r.objective <= r.initial_objective))
      invariant_violations_.push_back(step + "R above its start-of-step value");
    if (!(r.sliding_violation <= 1e-8))
      invariant_violations_.push_back(step + "boundary sliding violation " + std::to_string(r.sliding_violation));
    check_invariants(report);
  }

  template <int dim>
  void Simulation<dim>::check_invariants(StepReport &report)
  {
    if (contact_)
      report.min_distance = contact_->minimum_distance(state());
    report.min_reference_measure = min_cell_measure(mesh_, u_, false);
    report.min_deformed_jacobian = min_deformed_jacobian(mesh_, x_, u_);
    const std::string step = "step " + std::to_string(step_) + ": ";
    if (!(report.min_distance > 0))
      invariant_violations_.push_back(step + "minimum distance " + std::to_string(report.min_distance));
    if (!(report.min_reference_measure > 0))
      invariant_violations_.push_back(step + "inverted reference element");
    if (!(report.min_deformed_jacobian > 0))
      invariant_violations_.push_back(step + "inverted element (det F = " +
                                      std::to_string(report.min_deformed_jacobian) + ")");
  }

  template <int dim>
  Eigen::VectorXd Simulation<dim>::contact_forces() const
  {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(x_.size());
    if (!contact_)
      return f;
    Eigen::VectorXd g = Eigen::VectorXd::Zero(x_.size() + obstacle_positions_.size());
    const Eigen::VectorXd z = state();
    contact_->add_gradient(z, contact_->candidates_at(z), g);
    const double weight = scene_.dynamic() ? scene_.time_step * scene_.time_step : 1.0;
    return -g.head(x_.size()) / weight;
  }

  template class Simulation<1>;
  template class Simulation<2>;
  template class Simulation<3>;
} // namespace ritr
