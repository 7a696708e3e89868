#include <ritr/common/memory_estimate.h>
#include <ritr/output/run_directory.h>
#include <ritr/scene/expression.h>
#include <ritr/scene/parameter_text.h>
#include <ritr/scene/parameters.h>
#include <ritr/scene/scene_file.h>

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace ritr
{
  namespace
  {
    using dealii::ParameterHandler;
    namespace Patterns = dealii::Patterns;

    // A vector expression left at zero ("" in the scene structs) reads this in any dimension.
    const std::string zero_vector = "0;0;0";

    const auto doubles  = [] { return Patterns::List(Patterns::Double(), 0, 3); };
    const auto unsigneds = [] { return Patterns::List(Patterns::Integer(0), 0, 3); };

    void declare(ParameterHandler &prm)
    {
      const Scene defaults;  // of the top-level and Gravity entries
      prm.declare_entry("dimension", prm_value(defaults.dimension), Patterns::Integer(1, 3), "Spatial dimension: 1 (rods), 2 (triangles, plane strain), 3 (tetrahedra).");
      prm.declare_entry("mode", defaults.mode, Patterns::Selection("dynamic|static"),
                        "dynamic: implicit Euler elastodynamics; static: a sequence of equilibria (load-stepped in pseudo-time t).");
      prm.declare_entry("time step", prm_value(defaults.time_step), Patterns::Double(0), "Time step h (dynamic) or load step (static).");
      prm.declare_entry("end time", prm_value(defaults.end_time), Patterns::Double(0), "Simulated time: a whole number of time steps (the last step lands on it).");
      prm.declare_entry("output directory", defaults.output_directory, Patterns::Anything(), "Where results are written (created if missing; relative to the working directory).");
      prm.declare_entry("output every", prm_value(defaults.output_every), Patterns::Integer(1), "Write VTU files every this many steps (log.csv gets every step).");
      prm.declare_entry("write nodal csv", prm_value(defaults.write_nodal_csv), Patterns::Bool(), "Also write nodes-NNNNN.csv with id, u, x, v per node.");
      prm.declare_entry("start from", defaults.start_from, Patterns::Anything(), "A frame of another run of this scene (its solution-NNNNN.vtu, relative to the .prm file) to start from, on this scene's mesh: the run begins at the frame's time (from the solution.pvd beside it) with the frame's deformed positions and velocities at this mesh's reference nodes, interpolated linearly in the frame's reference cells; Dirichlet nodes and obstacles take their positions at that time. Dynamic scenes only; empty: start at t = 0 from the scene's initial state.");

      const BodyDescription body;
      for (unsigned int b = 0; b < max_bodies; ++b)
        {
          prm.enter_subsection("Body " + std::to_string(b));
          prm.declare_entry("enabled", b == 0 ? "true" : "false", Patterns::Bool(), "Whether this body exists.");
          prm.declare_entry("shape", body.shape, Patterns::Selection("interval|rectangle|box|disk|ball|file"), "interval (1D), rectangle (2D), box (3D), disk (2D), ball (3D) or file (gmsh .msh).");
          prm.declare_entry("file", body.file, Patterns::Anything(), "gmsh mesh for shape = file, relative to the .prm file. Physical tags give material and boundary ids.");
          prm.declare_entry("lower", prm_value(body.lower), doubles(), "Lower corner (interval/rectangle/box): dim numbers.");
          prm.declare_entry("upper", prm_value(body.upper), doubles(), "Upper corner (interval/rectangle/box): dim numbers.");
          prm.declare_entry("subdivisions", prm_value(body.subdivisions), unsigneds(), "Cells per direction before splitting into simplices: dim numbers.");
          prm.declare_entry("center", prm_value(body.center), doubles(), "Centre of a disk or ball: dim numbers.");
          prm.declare_entry("radius", prm_value(body.radius), Patterns::Double(0), "Radius of a disk or ball.");
          prm.declare_entry("shape refinements", prm_value(body.shape_refinements), Patterns::Integer(0, 8), "Refinements of a disk/ball that follow its round boundary.");
          prm.declare_entry("refinements", prm_value(body.refinements), Patterns::Integer(0, 8), "Uniform refinements by edge subdivision (each multiplies the cell count by 2^dim).");
          prm.declare_entry("translation", prm_value(body.translation), doubles(), "Shift applied to the body: dim numbers.");
          prm.declare_entry("material id", prm_value(body.material_id), Patterns::Integer(0, max_materials - 1), "Material of generated bodies (files use their physical tags).");
          prm.declare_entry("initial velocity", zero_vector, Patterns::Anything(), "Initial velocity field: dim components separated by ';', in x,y,z.");
          prm.leave_subsection();
        }
      const Material material;
      for (unsigned int m = 0; m < max_materials; ++m)
        {
          prm.enter_subsection("Material " + std::to_string(m));
          prm.declare_entry("model", name_of(material_model_names, material.model),
                            Patterns::Selection(selection(material_model_names)), "Hyperelastic model.");
          prm.declare_entry("youngs modulus", prm_value(material.youngs_modulus), Patterns::Double(0), "Young's modulus E [Pa].");
          prm.declare_entry("poisson ratio", prm_value(material.poisson_ratio), Patterns::Double(0, 0.5), "Poisson's ratio (ignored in 1D: a rod's modulus is E).");
          prm.declare_entry("density", prm_value(material.density), Patterns::Double(0), "Mass density [kg/m^dim].");
          prm.leave_subsection();
        }
      prm.enter_subsection("Gravity");
      prm.declare_entry("acceleration", prm_value(defaults.gravity), doubles(), "Body force per unit mass: dim numbers.");
      prm.declare_entry("load factor", defaults.load_factor, Patterns::Anything(), "Scalar expression in t scaling gravity (load stepping in statics, e.g. t/T).");
      prm.leave_subsection();
      const DirichletScene dirichlet;
      for (unsigned int d = 0; d < max_dirichlet; ++d)
        {
          prm.enter_subsection("Dirichlet " + std::to_string(d));
          prm.declare_entry("enabled", "false", Patterns::Bool(), "Whether this condition is applied.");
          prm.declare_entry("boundary ids", prm_value(dirichlet.boundary_ids), unsigneds(), "Nodes on boundary facets with these ids are prescribed.");
          prm.declare_entry("region", dirichlet.region, Patterns::Anything(), "Or: nodes where this expression of x,y,z is > 0 (e.g. 'x < 1e-6').");
          prm.declare_entry("displacement", zero_vector, Patterns::Anything(), "Prescribed displacement: dim components in x,y,z,t.");
          prm.declare_entry("sliding reference nodes", prm_value(dirichlet.sliding_reference_nodes), Patterns::Bool(), "r-ITR: the condition's reference nodes slide along its boundary (its nodes at the boundary's ends and corners stay), each prescribing the material point it moves to: x = u + displacement. Needs a displacement that is the same at every node, Adaptivity/hessian = reduced and admissibility = both. The paper's default for a clamped base; false holds the nodes (its supplemental variant).");
          prm.leave_subsection();
        }
      const ObstacleScene obstacle;
      for (unsigned int o = 0; o < max_obstacles; ++o)
        {
          prm.enter_subsection("Obstacle " + std::to_string(o));
          prm.declare_entry("type", obstacle.type, Patterns::Selection("none|plane|box|spikes|punch|file"), "Rigid obstacle: none, plane (ground), box, spikes (a row of sharp spikes), punch (a bar), file (.obj or .msh surface).");
          prm.declare_entry("file", obstacle.file, Patterns::Anything(), "Surface mesh for type = file, relative to the .prm file.");
          prm.declare_entry("point", prm_value(obstacle.point), doubles(), "plane: a point on it; box/punch: centre; spikes: centre of the row's base (dim numbers).");
          prm.declare_entry("normal", prm_value(obstacle.normal), doubles(), "plane: outward normal (the side where bodies are; dim numbers).");
          prm.declare_entry("size", prm_value(obstacle.size), doubles(), "plane: extent (one number); box/punch: edge lengths (dim numbers); spikes: row length (one number; a 3D row is as deep as it is long).");
          prm.declare_entry("count", prm_value(obstacle.count), Patterns::Integer(1), "spikes: number of spikes (per row direction).");
          prm.declare_entry("spike height", prm_value(obstacle.spike_height), Patterns::Double(0), "spikes: height of each spike.");
          prm.declare_entry("translation", zero_vector, Patterns::Anything(), "Scripted translation: dim components in t.");
          prm.declare_entry("rotation angle", "0", Patterns::Anything(), "Scripted rotation angle [rad] in t, about the rotation center (and axis in 3D).");
          prm.declare_entry("rotation axis", prm_value(obstacle.rotation_axis), doubles(), "3D rotation axis (3 numbers).");
          prm.declare_entry("rotation center", prm_value(obstacle.rotation_center), doubles(), "Centre of rotation (dim numbers).");
          prm.leave_subsection();
        }
      ContactScene::declare_parameters(prm);
      AdaptivityScene::declare_parameters(prm);
      SolverScene::declare_parameters(prm);
    }

    // Calls read(name) inside every enabled numbered subsection "KIND i", i < count.
    template <typename Read>
    void for_each_enabled(ParameterHandler &prm, const std::string &kind, const unsigned int count, Read read)
    {
      for (unsigned int i = 0; i < count; ++i)
        {
          const std::string name = kind + " " + std::to_string(i);
          prm.enter_subsection(name);
          if (prm.get_bool("enabled"))
            read(name);
          prm.leave_subsection();
        }
    }

    // The pattern has checked each item; strtod, unlike stod, does not throw on underflow.
    std::vector<double> get_doubles(ParameterHandler &prm, const std::string &name)
    {
      std::vector<double> v;
      std::stringstream   ss(prm.get(name));
      std::string         item;
      while (std::getline(ss, item, ','))
        v.push_back(std::strtod(item.c_str(), nullptr));
      return v;
    }

    // A list set in the file must give exactly `n` numbers: a short one is not padded with
    // zeros. Left at its default (three numbers), its first dim are used.
    std::vector<double> get_numbers(ParameterHandler &prm, const Scene &scene, const std::string &section,
                                    const std::string &name, const unsigned int n)
    {
      const std::vector<double> v     = get_doubles(prm, name);
      const std::string         entry = section.empty() ? name : section + "/" + name;
      if (scene.entry_lines.count(entry) > 0 && v.size() != n)
        throw InputError(scene.where(entry) + ": needs " + std::to_string(n) + (n == 1 ? " number" : " numbers") +
                         (n == static_cast<unsigned int>(scene.dimension) && n > 1 ? " (one per direction)" : "") +
                         ", not " + std::to_string(v.size()));
      return v;
    }
    std::vector<unsigned int> to_unsigned(const std::vector<double> &numbers)
    {
      return std::vector<unsigned int>(numbers.begin(), numbers.end());
    }

    // Compiles an expression so that a typo is reported at start-up with its entry name.
    void check_expression(const int dim, const std::string &text, const unsigned int components,
                          const std::string &where)
    {
      try
        {
          if (dim == 1)
            Expression<1>(text, components);
          else if (dim == 2)
            Expression<2>(text, components);
          else
            Expression<3>(text, components);
        }
      catch (const std::exception &e)
        {
          throw InputError(where + ": " + e.what());
        }
    }

    // Vector expressions left at zero_vector mean zero in any dimension.
    std::string vector_expression(ParameterHandler &prm, const std::string &name, const int dim)
    {
      const std::string text = prm.get(name);
      if (text != zero_vector)
        return text;
      return dim == 1 ? "0" : dim == 2 ? "0;0" : "0;0;0";
    }

    std::string resolve(const std::string &path, const std::string &prm_file)
    {
      if (path.empty() || path[0] == '/')
        return path;
      const auto slash = prm_file.find_last_of('/');
      return slash == std::string::npos ? path : prm_file.substr(0, slash + 1) + path;
    }

    // Refuses (through `fail`) a row of spikes too large for memory: `count` spikes make
    // 2 count segments in 2D, 4 count^2 triangles in 3D, each with at least this much memory
    // (measured: 830 bytes per triangle through the first step).
    template <typename Fail>
    void check_spike_count(const double count, const int dim, const Fail &fail)
    {
      constexpr double bytes_per_facet = 500;
      const double     facets          = dim == 2 ? 2 * count : 4 * count * count;
      if (const std::string problem = memory_problem(facets, bytes_per_facet, dim == 2 ? "segments" : "triangles");
          !problem.empty())
        fail(std::to_string(static_cast<long long>(count)) + " spikes " + problem);
    }

    // Whether an expression is the constant zero ("0", "0.0", " -0 ").
    bool is_constant_zero(const std::string &expression)
    {
      char        *end   = nullptr;
      const double value = std::strtod(expression.c_str(), &end);
      return end != expression.c_str() && std::string(end).find_first_not_of(" \t") == std::string::npos && value == 0;
    }

    // Refuses (through `fail(entry, what)`) an obstacle's directions that define nothing: a
    // plane's zero normal (it would collapse to a point) and, in 3D, a zero rotation axis of
    // an obstacle that rotates (the rotation would shrink it).
    template <typename Fail>
    void check_directions(const ObstacleScene &obstacle, const int dim, const Fail &fail)
    {
      const auto length = [&](const std::vector<double> &v, const int n) {
        double squares = 0;
        for (int k = 0; k < n; ++k)
          squares += v[k] * v[k];
        return std::sqrt(squares);
      };
      if (obstacle.type == "plane" && !(length(obstacle.normal, dim) > 0 && std::isfinite(length(obstacle.normal, dim))))
        fail("normal", "must be a nonzero direction");
      if (dim == 3 && !is_constant_zero(obstacle.rotation_angle) &&
          !(length(obstacle.rotation_axis, 3) > 0 && std::isfinite(length(obstacle.rotation_axis, 3))))
        fail("rotation axis", "must be a nonzero direction when the obstacle rotates (rotation angle '" +
                                shortened(obstacle.rotation_angle) + "')");
    }

    // The scene of a parsed parameter file, with every check that needs more than a pattern.
    Scene validated_scene(ParameterHandler &prm, const SceneFile &scene_file, const std::string &file)
    {
      Scene s;
      s.parameter_file   = file;
      s.entry_lines      = scene_file.lines;
      s.dimension        = prm.get_integer("dimension");
      s.mode             = prm.get("mode");
      s.time_step        = prm.get_double("time step");
      s.end_time         = prm.get_double("end time");
      s.output_directory = prm.get("output directory");
      s.output_every     = prm.get_integer("output every");
      s.write_nodal_csv  = prm.get_bool("write nodal csv");
      if (!prm.get("start from").empty())
        s.start_from = resolve(prm.get("start from"), file);
      const int dim      = s.dimension;
      const auto fail    = [&](const std::string &entry, const std::string &what) {
        throw InputError(s.where(entry) + ": " + what);
      };
      if (!(s.time_step > 0))
        fail("time step", "must be positive");
      if (!(s.end_time > 0))
        fail("end time", "must be positive");
      if (s.time_step > s.end_time)
        fail("time step", "exceeds the end time (" + prm.get("end time") + ")");
      // The last step lands on the end time: a whole number of steps, countable in an int.
      const double steps = s.end_time / s.time_step;
      if (!(steps <= std::numeric_limits<int>::max()))
        fail("time step", "gives more than " + std::to_string(std::numeric_limits<int>::max()) + " steps");
      if (std::abs(steps - std::round(steps)) > 1e-6)
        fail("end time", "is not a whole number of time steps of " + prm.get("time step") + " (" +
                           std::to_string(steps) + " steps)");
      if (!s.start_from.empty() && !s.dynamic())
        fail("start from", "needs a dynamic scene (mode = dynamic)");
      if (s.output_directory.empty())
        fail("output directory", "is empty");
      if (const std::string problem = output_directory_problem(s.output_directory); !problem.empty())
        fail("output directory", "'" + shortened(s.output_directory) + "' " + problem);

      for_each_enabled(prm, "Body", max_bodies, [&](const std::string &name) {
        BodyScene body;
        body.section        = name;
        auto     &g         = body.geometry;
        g.shape             = prm.get("shape");
        g.file              = resolve(prm.get("file"), file);
        g.lower             = get_numbers(prm, s, name, "lower", dim);
        g.upper             = get_numbers(prm, s, name, "upper", dim);
        g.subdivisions      = to_unsigned(get_numbers(prm, s, name, "subdivisions", dim));
        g.center            = get_numbers(prm, s, name, "center", dim);
        g.radius            = prm.get_double("radius");
        g.shape_refinements = prm.get_integer("shape refinements");
        g.refinements       = prm.get_integer("refinements");
        g.translation       = get_numbers(prm, s, name, "translation", dim);
        g.material_id       = prm.get_integer("material id");
        body.initial_velocity = vector_expression(prm, "initial velocity", dim);
        if (g.shape == "file" && g.file.empty())
          fail(name + "/file", "shape = file needs a mesh file");
        if (g.shape == "file" && !std::ifstream(g.file))
          fail(name + "/file", "cannot open mesh file '" + shortened(g.file) + "'");
        if (g.shape != "file" && g.shape != "disk" && g.shape != "ball")
          for (int k = 0; k < dim; ++k)
            if (k >= static_cast<int>(g.lower.size()) || k >= static_cast<int>(g.upper.size()) ||
                !(g.upper[k] > g.lower[k]))
              fail(name + "/upper", "must exceed 'lower' in each of the " + std::to_string(dim) + " directions");
        check_expression(dim, body.initial_velocity, dim, s.where(name + "/initial velocity"));
        s.bodies.push_back(body);
      });
      if (s.bodies.empty())
        fail("Body 0/enabled", "the scene has no body");

      for (unsigned int m = 0; m < max_materials; ++m)
        {
          prm.enter_subsection("Material " + std::to_string(m));
          Material mat;
          mat.model          = material_model_from(prm.get("model"));
          mat.youngs_modulus = prm.get_double("youngs modulus");
          mat.poisson_ratio  = prm.get_double("poisson ratio");
          mat.density        = prm.get_double("density");
          if (!(mat.youngs_modulus > 0) || !(mat.density > 0) || !(mat.poisson_ratio < 0.5))
            fail("Material " + std::to_string(m), "needs E > 0, density > 0 and Poisson ratio < 0.5");
          s.materials.push_back(mat);
          prm.leave_subsection();
        }

      prm.enter_subsection("Gravity");
      s.gravity     = get_numbers(prm, s, "Gravity", "acceleration", dim);
      s.gravity.resize(3, 0.0);
      s.load_factor = prm.get("load factor");
      check_expression(dim, s.load_factor, 1, s.where("Gravity/load factor"));
      prm.leave_subsection();

      for_each_enabled(prm, "Dirichlet", max_dirichlet, [&](const std::string &name) {
        DirichletScene bc;
        bc.section      = name;
        bc.boundary_ids = to_unsigned(get_doubles(prm, "boundary ids"));
        bc.region       = prm.get("region");
        bc.displacement = vector_expression(prm, "displacement", dim);
        bc.sliding_reference_nodes = prm.get_bool("sliding reference nodes");
        if (bc.boundary_ids.empty() == bc.region.empty())
          fail(name, "give exactly one of 'boundary ids' and 'region'");
        if (!bc.region.empty())
          check_expression(dim, bc.region, 1, s.where(name + "/region"));
        check_expression(dim, bc.displacement, dim, s.where(name + "/displacement"));
        s.dirichlet.push_back(bc);
      });

      for (unsigned int o = 0; o < max_obstacles; ++o)
        {
          const std::string name = "Obstacle " + std::to_string(o);
          prm.enter_subsection(name);
          ObstacleScene ob;
          ob.section = name;
          ob.type    = prm.get("type");
          if (ob.type != "none")
            {
              ob.file            = resolve(prm.get("file"), file);
              const bool box     = ob.type == "box" || ob.type == "punch";
              ob.point           = get_numbers(prm, s, name, "point", dim);
              ob.normal          = get_numbers(prm, s, name, "normal", dim);
              ob.size            = get_numbers(prm, s, name, "size", box ? dim : 1);
              const double count = prm.get_integer("count");
              if (ob.type == "spikes" && dim > 1)
                check_spike_count(count, dim, [&](const std::string &what) { fail(name + "/count", what); });
              ob.count           = static_cast<unsigned int>(count);
              ob.spike_height    = prm.get_double("spike height");
              ob.translation     = vector_expression(prm, "translation", dim);
              ob.rotation_angle  = prm.get("rotation angle");
              ob.rotation_axis   = get_numbers(prm, s, name, "rotation axis", 3);
              ob.rotation_center = get_numbers(prm, s, name, "rotation center", dim);
              for (auto *v : {&ob.point, &ob.normal, &ob.size, &ob.rotation_axis, &ob.rotation_center})
                v->resize(3, 0.0);
              if (ob.type == "file" && !std::ifstream(ob.file))
                fail(name + "/file", "cannot open obstacle file '" + shortened(ob.file) + "'");
              if (dim == 1 && ob.type != "plane")
                fail(name + "/type", "in 1D only 'plane' obstacles (walls) exist");
              check_expression(dim, ob.translation, dim, s.where(name + "/translation"));
              check_expression(dim, ob.rotation_angle, 1, s.where(name + "/rotation angle"));
              check_directions(ob, dim, [&](const std::string &entry, const std::string &what) {
                fail(name + "/" + entry, what);
              });
              s.obstacles.push_back(ob);
            }
          prm.leave_subsection();
        }

      try
        {
          s.contact.parse_parameters(prm);
          s.adaptivity.parse_parameters(prm);
          s.solver.parse_parameters(prm);
        }
      catch (const EntryError &e)
        {
          fail(e.entry, e.what());
        }
      return s;
    }
  } // namespace

  unsigned int Scene::n_steps() const { return std::max(1L, std::lround((end_time - start_time) / time_step)); }

  std::string Scene::where(const std::string &entry) const
  {
    const auto line = entry_lines.find(entry);
    return parameter_file + (line == entry_lines.end() ? "" : ":" + std::to_string(line->second)) + ": " + entry;
  }

  void print_parameters(std::ostream &out)
  {
    ParameterHandler prm;
    declare(prm);
    prm.print_parameters(out, ParameterHandler::OutputStyle::PRM);
  }

  std::vector<std::pair<std::string, std::string>> listing_entries(const std::string &listing)
  {
    std::istringstream                               lines(listing);
    std::vector<std::string>                         sections;
    std::vector<std::pair<std::string, std::string>> entries;
    const auto trimmed = [](const std::string &text) {
      const auto first = text.find_first_not_of(" \t"), last = text.find_last_not_of(" \t\r");
      return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
    };
    for (std::string line; std::getline(lines, line);)
      {
        line = trimmed(line);
        if (line.rfind("subsection ", 0) == 0)
          sections.push_back(trimmed(line.substr(11)));
        else if (line == "end" && !sections.empty())
          sections.pop_back();
        else if (const auto equals = line.find('='); line.rfind("set ", 0) == 0 && equals != std::string::npos)
          {
            std::string path;
            for (const auto &section : sections)
              path += section + "/";
            entries.emplace_back(path + trimmed(line.substr(4, equals - 4)), trimmed(line.substr(equals + 1)));
          }
      }
    return entries;
  }

  namespace
  {
    // Where the outputs go and how many threads assemble or factorize do not change the
    // results beyond round-off: a moved output directory resumes, and so does a run on
    // another machine. Nor does the end time change the steps before it: a finished run
    // resumed with a later one goes on. Nor the Newton cap: it only decides where a run stops,
    // so a run stopped on it resumes with a larger one.
    const std::array<std::string, 5> same_run_entries = {
      {"output directory", "end time", "Solver/threads", "Solver/factorization threads", "Solver/max iterations"}};

    // "set Section/entry = value", one line per entry whose value differs from its default,
    // but for those that leave the run unchanged, in the listing's order (listing_entries
    // reads it back). Entries left at their defaults are left out, so that an entry a newer
    // ritr declares does not make a scene another scene.
    std::string entries_away_from_defaults(const ParameterHandler &prm)
    {
      ParameterHandler defaults;
      declare(defaults);
      const auto printed = [](const ParameterHandler &p) {
        std::ostringstream out;
        p.print_parameters(out, ParameterHandler::OutputStyle::ShortPRM);
        return listing_entries(out.str());
      };
      const auto  default_entries = printed(defaults);  // the same entries, in the same order
      const auto  entries         = printed(prm);
      std::string listing;
      for (std::size_t i = 0; i < entries.size(); ++i)
        if (entries[i] != default_entries[i] && !leaves_the_run_unchanged(entries[i].first))
          listing += "set " + entries[i].first + " = " + entries[i].second + "\n";
      return listing;
    }
  } // namespace

  bool leaves_the_run_unchanged(const std::string &entry)
  {
    return std::find(same_run_entries.begin(), same_run_entries.end(), entry) != same_run_entries.end();
  }

  Scene read_scene(const std::string &file)
  {
    const SceneFile  scene_file = read_scene_file(file);
    ParameterHandler prm;
    declare(prm);
    try
      {
        std::istringstream text(scene_file.text);
        prm.parse_input(text, file, "", false);
        if (!scene_file.sets_an_entry)
          throw InputError(file + ": sets no entry (an empty scene would run every default)");
        Scene scene = validated_scene(prm, scene_file, file);
        scene.parameter_listing = entries_away_from_defaults(prm);
        return scene;
      }
    catch (const InputError &)
      {
        throw;
      }
    // deal.II reports what its parser rejects, or a value it cannot convert, in its own
    // exceptions: several lines that name the file or the entry.
    catch (const dealii::ExceptionBase &e)
      {
        std::stringstream ss;
        e.print_info(ss);
        throw InputError(fold_parser_message(ss.str(), file, scene_file));
      }
    catch (const std::exception &e)
      {
        throw InputError(fold_parser_message(e.what(), file, scene_file));
      }
  }
} // namespace ritr
