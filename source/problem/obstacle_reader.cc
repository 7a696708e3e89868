#include <ritr/mesh/gmsh_checks.h>
#include <ritr/problem/obstacle_reader.h>

#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <fstream>
#include <stdexcept>

namespace ritr
{
  template <int dim>
  contact::RigidObstacle<dim> read_obstacle_msh(const std::string &file)
  {
    contact::RigidObstacle<dim> obstacle;
    if constexpr (dim == 1)
      throw std::runtime_error("obstacle meshes do not exist in 1D (use a plane)");
    else
      {
        std::ifstream in(file);
        if (!in)
          throw std::runtime_error("cannot open obstacle file '" + file + "'");
        dealii::Triangulation<dim - 1, dim> surface;
        check_unique_node_tags(file);
        check_unique_elements(file, dim - 1);
        dealii::GridIn<dim - 1, dim>        grid_in(surface);
        try
          {
            grid_in.read_msh(in);
          }
        catch (const std::exception &)
          {
            throw std::runtime_error("obstacle file '" + file + "' is not a readable gmsh " +
                                     (dim == 2 ? "line" : "triangle") + " mesh");
          }
        for (const auto &v : surface.get_vertices())
          {
            Eigen::Matrix<double, dim, 1> p;
            for (int k = 0; k < dim; ++k)
              p[k] = v[k];
            obstacle.rest_vertices.push_back(p);
          }
        for (const auto &cell : surface.active_cell_iterators())
          {
            if (cell->n_vertices() != static_cast<unsigned int>(dim))
              throw std::runtime_error("obstacle file '" + file + "' must contain only " +
                                       (dim == 2 ? "line" : "triangle") + " elements");
            if constexpr (dim == 2)
              obstacle.edges.push_back({{static_cast<int>(cell->vertex_index(0)), static_cast<int>(cell->vertex_index(1))}});
            else
              obstacle.faces.push_back({{static_cast<int>(cell->vertex_index(0)), static_cast<int>(cell->vertex_index(1)),
                                         static_cast<int>(cell->vertex_index(2))}});
          }
        for (const auto &p : obstacle.rest_vertices)
          if (!p.allFinite())
            throw std::runtime_error("obstacle file '" + file + "' has a vertex that is not finite");
        if (const int e = contact::first_degenerate_element(obstacle); e >= 0)
          throw std::runtime_error("obstacle file '" + file + "' has " +
                                   (dim == 2 ? "a segment of zero length (segment " : "a triangle of zero area (triangle ") +
                                   std::to_string(e + 1) + ")");
      }
    return obstacle;
  }

  template contact::RigidObstacle<1> read_obstacle_msh<1>(const std::string &);
  template contact::RigidObstacle<2> read_obstacle_msh<2>(const std::string &);
  template contact::RigidObstacle<3> read_obstacle_msh<3>(const std::string &);
} // namespace ritr
