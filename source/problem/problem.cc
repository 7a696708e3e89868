#include <ritr/common/input_error.h>
#include <ritr/contact/obj_file.h>
#include <ritr/problem/obstacle_reader.h>
#include <ritr/problem/problem.h>

#include <algorithm>
#include <cmath>
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
  std::unique_ptr<Problem<dim>> make_problem(const Scene &scene, const WorkShare &share)
  {
    std::unique_ptr<Problem<dim>> p(new Problem<dim>());
    p->scene      = scene;
    p->work_share = share;
    p->build_mesh_and_materials();
    p->set_initial_velocity();
    p->build_obstacles();
    p->build_dirichlet_conditions();
    p->start_from_frame();
    p->build_contact();
    p->share_cells();
    p->build_terms();
    p->check_initial_state();
    return p;
  }

  template <int dim>
  void Problem<dim>::build_mesh_and_materials()
  {
    std::vector<BodyDescription> bodies;
    for (const auto &b : scene.bodies)
      bodies.push_back(b.geometry);
    try
      {
        mesh = build_mesh<dim>(bodies);
        materials = std::make_unique<CellMaterials<dim>>(mesh, scene.materials);
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
    initial_reference = mesh.reference;
    initial_positions = initial_reference;
  }

  template <int dim>
  void Problem<dim>::set_initial_velocity()
  {
    initial_velocity = Eigen::VectorXd::Zero(initial_reference.size());
    std::vector<Expression<dim>> velocity;
    std::vector<std::string>     velocity_entry;
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
      {
        velocity.emplace_back(scene.bodies[b].initial_velocity, dim);
        velocity_entry.push_back(scene.where(section(scene.bodies[b].section, "Body", b) + "/initial velocity"));
      }
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      {
        const unsigned int b = mesh.node_part[i];
        initial_velocity.template segment<dim>(i * dim) =
          finite_value(velocity[b], mesh.reference_node(i), 0.0, velocity_entry[b]);
      }
    load_factor_.emplace(scene.load_factor, 1);
    for (const double t : {0.0, scene.time_step})
      finite_value<dim>(*load_factor_, Vec<dim>::Zero(), t, scene.where("Gravity/load factor"));
  }

  template <int dim>
  void Problem<dim>::build_obstacles()
  {
    for (std::size_t o = 0; o < scene.obstacles.size(); ++o)
      {
        const ObstacleScene &s    = scene.obstacles[o];
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
            throw InputError(scene.where(name) + ": " + e.what());
          }
        obstacle.center = to_vec<dim>(s.rotation_center);
        obstacle.axis   = Eigen::Vector3d(s.rotation_axis[0], s.rotation_axis[1], s.rotation_axis[2]);
        auto translation = std::make_shared<Expression<dim>>(s.translation, dim);
        auto angle       = std::make_shared<Expression<dim>>(s.rotation_angle, 1);
        for (const double t : {0.0, scene.time_step})
          {
            finite_value<dim>(*translation, Vec<dim>::Zero(), t, scene.where(name + "/translation"));
            finite_value<dim>(*angle, Vec<dim>::Zero(), t, scene.where(name + "/rotation angle"));
          }
        // Checked at every time the run evaluates them too: a motion that stops being finite
        // later is bad input named as such, not a failed step.
        obstacle.translation = [translation, entry = scene.where(name + "/translation")](double t) {
          return Vec<dim>(finite_value<dim>(*translation, Vec<dim>::Zero(), t, entry));
        };
        obstacle.angle = [angle, entry = scene.where(name + "/rotation angle")](double t) {
          return finite_value<dim>(*angle, Vec<dim>::Zero(), t, entry)[0];
        };
        obstacles.push_back(std::move(obstacle));
      }
    unsigned int n = 0;
    for (const auto &o : obstacles)
      n += o.rest_vertices.size();
    initial_obstacle_positions.resize(n * dim);
    for (unsigned int i = 0, o = 0; o < obstacles.size(); ++o)
      for (const auto &p : obstacles[o].vertices_at(0.0))
        initial_obstacle_positions.template segment<dim>(dim * i++) = p;
  }

  template <int dim>
  void Problem<dim>::build_dirichlet_conditions()
  {
    std::vector<int> condition_of(mesh.n_nodes(), -1);
    const auto       name = [&](const unsigned int d) { return section(scene.dirichlet[d].section, "Dirichlet", d); };
    for (unsigned int d = 0; d < scene.dirichlet.size(); ++d)
      {
        const DirichletScene &bc           = scene.dirichlet[d];
        const std::string     region_entry = scene.where(name(d) + "/region");
        const std::string     displacement_entry = scene.where(name(d) + "/displacement");
        std::vector<bool>     selected(mesh.n_nodes(), false);
        if (!bc.region.empty())
          {
            const Expression<dim> region(bc.region, 1);
            for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
              selected[i] = finite_value(region, mesh.reference_node(i), 0.0, region_entry)[0] > 0;
          }
        else
          for (unsigned int f = 0; f < mesh.boundary_facets.size(); ++f)
            if (std::find(bc.boundary_ids.begin(), bc.boundary_ids.end(), mesh.boundary_ids[f]) !=
                bc.boundary_ids.end())
              for (const unsigned int n : mesh.boundary_facets[f])
                selected[n] = true;
        dirichlet_displacements_.emplace_back(bc.displacement, dim);
        dirichlet_entries_.push_back(displacement_entry);
        unsigned int count = 0;
        for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
          if (selected[i])
            {
              ++count;
              for (const double t : {0.0, scene.time_step})
                finite_value(dirichlet_displacements_[d], mesh.reference_node(i), t, displacement_entry);
              if (condition_of[i] >= 0)
                {
                  // Two conditions on one node must agree at all times we can check cheaply.
                  for (const double t : {0.0, 0.5 * scene.end_time, scene.end_time})
                    if ((dirichlet_displacements_[condition_of[i]].vector_value(mesh.reference_node(i), t) -
                         dirichlet_displacements_[d].vector_value(mesh.reference_node(i), t))
                          .norm() > 1e-12)
                      throw InputError(scene.where(name(d)) + ": contradicts " + name(condition_of[i]) +
                                       " on shared nodes");
                  continue;
                }
              condition_of[i] = d;
              dirichlet_nodes_.emplace_back(i, d);
              if (bc.sliding_reference_nodes)
                sliding_dirichlet_nodes.emplace_back(i, d);
            }
        if (count == 0)
          throw InputError(scene.where(name(d)) + ": selects no node");
        if (bc.sliding_reference_nodes)
          {
            // A sliding node prescribes whichever material point it carries: that is the
            // condition only where the displacement is the same for all of them.
            const std::string entry = scene.where(name(d) + "/sliding reference nodes");
            if (sliding_dirichlet_entry.empty())
              sliding_dirichlet_entry = entry;
            // At every step's time (the nodes visit points between the sampled nodes, so this
            // is a sample too, the one the simulation evaluates).
            for (unsigned int step = 0; step <= scene.n_steps(); ++step)
              {
                const double t = std::min(step * scene.time_step, scene.end_time);
                std::optional<Eigen::VectorXd> first;
                for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
                  if (selected[i])
                    {
                      const Eigen::VectorXd g = dirichlet_displacements_[d].vector_value(mesh.reference_node(i), t);
                      if (!first)
                        first = g;
                      else if ((g - *first).norm() > 1e-12 * (1 + first->norm()))
                        throw InputError(entry + ": needs a displacement that is the same at every node of the condition");
                    }
              }
          }
      }
    kinematic.assign(initial_reference.size() + initial_obstacle_positions.size(), false);
    for (const auto &[node, condition] : dirichlet_nodes_)
      for (int k = 0; k < dim; ++k)
        kinematic[node * dim + k] = true;
    for (Eigen::Index i = initial_reference.size(); i < static_cast<Eigen::Index>(kinematic.size()); ++i)
      kinematic[i] = true;
    // Dirichlet nodes start at their prescribed position.
    const Eigen::VectorXd start = targets(0.0);
    for (const auto &[node, condition] : dirichlet_nodes_)
      initial_positions.template segment<dim>(node * dim) = start.template segment<dim>(node * dim);
  }

  template <int dim>
  void Problem<dim>::build_contact()
  {
    if (scene.contact.enabled)
      collisions = std::make_unique<CollisionMesh<dim>>(mesh, obstacles, scene.contact.dhat, scene.contact.self_contact);
  }

  template <int dim>
  Eigen::VectorXd Problem<dim>::targets(const double t) const
  {
    Eigen::VectorXd z = Eigen::VectorXd::Zero(initial_reference.size() + initial_obstacle_positions.size());
    for (const auto &[node, condition] : dirichlet_nodes_)
      z.template segment<dim>(node * dim) =
        mesh.reference_node(node) +
        Vec<dim>(finite_value(dirichlet_displacements_[condition], mesh.reference_node(node), t, dirichlet_entries_[condition]));
    unsigned int i = mesh.n_nodes();
    for (const auto &o : obstacles)
      for (const auto &p : o.vertices_at(t))
        z.template segment<dim>(dim * i++) = p;
    return z;
  }

  template <int dim>
  std::array<double, dim> Problem<dim>::gravity(const double t) const
  {
    const double load = finite_value<dim>(*load_factor_, Vec<dim>::Zero(), t, scene.where("Gravity/load factor"))[0];
    std::array<double, dim> g;
    for (int k = 0; k < dim; ++k)
      g[k] = scene.gravity[k] * load;
    return g;
  }

  template class Problem<1>;
  template class Problem<2>;
  template class Problem<3>;
  template std::unique_ptr<Problem<1>> make_problem<1>(const Scene &, const WorkShare &);
  template std::unique_ptr<Problem<2>> make_problem<2>(const Scene &, const WorkShare &);
  template std::unique_ptr<Problem<3>> make_problem<3>(const Scene &, const WorkShare &);
} // namespace ritr
