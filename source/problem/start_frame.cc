// The initial state taken from a frame of another run of the scene (`start from`): the run
// begins at the frame's time, and each node of this scene's mesh takes the deformed position
// and velocity of the material point at its reference position, interpolated linearly in the
// frame's reference cells. A frame of a coarser mesh thus starts a finer one from the same
// piecewise-linear state (exactly, when the fine mesh refines the coarse one), and a frame of
// an r-ITR run starts a fixed mesh from its state: how the paper's branch questions are put.
#include <ritr/common/input_error.h>
#include <ritr/common/number_text.h>
#include <ritr/output/vtk_reader.h>
#include <ritr/problem/problem.h>
#include <ritr/transfer/old_mesh_locator.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

namespace ritr
{
  namespace
  {

    // The time of `frame` in the solution.pvd beside it.
    double frame_time(const std::filesystem::path &frame, const std::string &entry)
    {
      const std::filesystem::path pvd = frame.parent_path() / "solution.pvd";
      std::vector<PvdFrame>       frames;
      try
        {
          frames = read_pvd(pvd);
        }
      catch (const InputError &e)
        {
          throw InputError(entry + ": " + frame.string() + " is not listed in " + pvd.string() + " (" + e.what() + ")");
        }
      for (const PvdFrame &f : frames)
        if (std::filesystem::exists(f.file) && std::filesystem::equivalent(f.file, frame))
          return f.time;
      throw InputError(entry + ": " + frame.string() + " is not listed in " + pvd.string());
    }

    // Column-wise (x, y[, z]) rows of a frame's field, packed per node like the state.
    template <int dim>
    Eigen::VectorXd packed(const Eigen::MatrixXd &rows)
    {
      Eigen::VectorXd v(rows.rows() * dim);
      for (Eigen::Index i = 0; i < rows.rows(); ++i)
        for (int k = 0; k < dim; ++k)
          v[i * dim + k] = rows(i, k);
      return v;
    }
  } // namespace

  template <int dim>
  void Problem<dim>::start_from_frame()
  {
    if (scene.start_from.empty())
      return;
    const std::string entry = scene.where("start from");
    if (!std::filesystem::is_regular_file(scene.start_from))
      throw InputError(entry + ": " + scene.start_from + ": no such file");
    const double start = frame_time(scene.start_from, entry);
    const double steps = (scene.end_time - start) / scene.time_step;
    if (!(start >= 0) || !(steps >= 1 - 1e-6))
      throw InputError(entry + ": the frame's time " + number_text(start) + " leaves no step before the end time");
    if (std::abs(steps - std::round(steps)) > 1e-6)
      throw InputError(entry + ": the frame's time " + number_text(start) + " is not a whole number of time steps before the end time");

    const VtuGrid frame = read_vtu(scene.start_from);
    const auto    field = [&](const std::string &name) -> const Eigen::MatrixXd & {
      const auto f = frame.point_fields.find(name);
      if (f == frame.point_fields.end() || f->second.rows() != static_cast<Eigen::Index>(frame.points.size()) ||
          f->second.cols() < dim)
        throw InputError(entry + ": " + scene.start_from + " has no point field '" + name + "' (not a ritr frame?)");
      return f->second;
    };
    if (frame.dim != static_cast<unsigned int>(dim))
      throw InputError(entry + ": " + scene.start_from + " is a frame of a " + std::to_string(frame.dim) + "D run, the scene is " +
                       std::to_string(dim) + "D");
    Eigen::MatrixXd deformed(frame.points.size(), 3);
    for (std::size_t i = 0; i < frame.points.size(); ++i)
      for (int k = 0; k < 3; ++k)
        deformed(i, k) = frame.points[i][k];
    const Eigen::VectorXd u_frame = packed<dim>(field("reference_position")), x_frame = packed<dim>(deformed),
                          v_frame = packed<dim>(field("velocity"));

    using Locator = transfer::OldMeshLocator<dim>;
    std::vector<typename Locator::Cell> cells;
    for (const auto &c : frame.cells)
      {
        typename Locator::Cell cell;
        for (int a = 0; a <= dim; ++a)
          cell[a] = c[a];
        cells.push_back(cell);
      }
    std::optional<Locator> locator;
    try
      {
        locator.emplace(cells, u_frame, 1e-9);
      }
    catch (const std::invalid_argument &e)
      {
        throw InputError(entry + ": " + scene.start_from + ": " + e.what());
      }
    // The frame's reference domain is the scene's (r-ITR moves nodes inside it, boundary nodes
    // along it): a node farther out than round-off belongs to another scene.
    double largest_extent = 0;
    for (Eigen::Index i = 0; i < u_frame.size(); ++i)
      largest_extent = std::max(largest_extent, std::abs(u_frame[i]));
    const double outside_tolerance = 1e-9 * std::max(1.0, largest_extent);
    int hint = -1;
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      {
        const Vec<dim>            X        = mesh.reference_node(i);
        const auto                location = hint < 0 ? locator->locate(X) : locator->locate(X, hint);
        if (!location.inside && locator->distance(location.cell, X) > outside_tolerance)
          {
            std::ostringstream s;
            s << entry << ": node " << i << " of the scene's mesh, at (" << X.transpose() << "), lies outside the reference domain of "
              << scene.start_from;
            throw InputError(s.str());
          }
        hint = location.cell;
        Vec<dim> x = Vec<dim>::Zero(), v = Vec<dim>::Zero();
        for (int a = 0; a <= dim; ++a)
          {
            const unsigned int node = locator->cell(location.cell)[a];
            x += location.barycentric[a] * x_frame.template segment<dim>(node * dim);
            v += location.barycentric[a] * v_frame.template segment<dim>(node * dim);
          }
        initial_positions.template segment<dim>(i * dim) = x;
        initial_velocity.template segment<dim>(i * dim)  = v;
      }
    // Prescribed entries where the scene puts them at the start time.
    scene.start_time            = start;
    const Eigen::VectorXd moved = targets(start);
    for (const auto &[node, condition] : dirichlet_nodes_)
      initial_positions.template segment<dim>(node * dim) = moved.template segment<dim>(node * dim);
    initial_obstacle_positions = moved.tail(initial_obstacle_positions.size());
  }

  template void Problem<1>::start_from_frame();
  template void Problem<2>::start_from_frame();
  template void Problem<3>::start_from_frame();
} // namespace ritr
