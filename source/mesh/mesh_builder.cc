#include <ritr/common/memory_estimate.h>
#include <ritr/common/small_matrix.h>
#include <ritr/mesh/gmsh_checks.h>
#include <ritr/mesh/mesh_builder.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numeric>
#include <stdexcept>

namespace ritr
{
  namespace
  {
    template <int dim>
    dealii::Point<dim> to_point(const std::vector<double> &v)
    {
      dealii::Point<dim> p;
      for (int k = 0; k < dim; ++k)
        p[k] = k < static_cast<int>(v.size()) ? v[k] : 0.0;
      return p;
    }

    // At least this much memory goes with each cell in a run (measured through the first
    // step: 4 KB per triangle, 14 KB per tetrahedron).
    constexpr double bytes_per_cell = 2000;

    // Throws before a body is made that could not fit in memory: `cells` before the body's
    // uniform refinements, made by `what`.
    template <int dim>
    void check_fits_in_memory(const double cells, const BodyDescription &body, const std::string &what)
    {
      const double refined = cells * std::pow(2.0, dim * static_cast<double>(body.refinements));
      if (const std::string problem = memory_problem(refined, bytes_per_cell, "cells"); !problem.empty())
        throw std::runtime_error(what + " and " + std::to_string(body.refinements) + " refinements " + problem);
    }

    // Generates (or reads) one body as a simplex triangulation (lines in 1D).
    template <int dim>
    void generate_body(const BodyDescription &body, dealii::Triangulation<dim> &tria)
    {
      using namespace dealii;
      if (body.shape == "file")
        {
          std::ifstream in(body.file);
          if (!in)
            throw std::runtime_error("cannot open mesh file '" + body.file + "'");
          check_unique_node_tags(body.file);
          check_unique_elements(body.file, dim);
          GridIn<dim> grid_in(tria);
          try
            {
              grid_in.read_msh(in);
            }
          catch (const std::exception &)
            {
              throw std::runtime_error("mesh file '" + body.file +
                                       "' is not a readable gmsh mesh of dimension " +
                                       std::to_string(dim));
            }
          check_fits_in_memory<dim>(tria.n_active_cells(), body,
                                    "the " + std::to_string(tria.n_active_cells()) + " cells of '" + body.file + "'");
        }
      else if (body.shape == "interval" || body.shape == "rectangle" || body.shape == "box")
        {
          const char *expected = dim == 1 ? "interval" : dim == 2 ? "rectangle" : "box";
          if (body.shape != expected)
            throw std::runtime_error("shape '" + body.shape + "' does not exist in dimension " +
                                     std::to_string(dim) + " (use '" + expected + "')");
          std::vector<unsigned int> subdivisions(dim);
          double                    boxes = 1;
          std::string               grid;
          for (int k = 0; k < dim; ++k)
            {
              subdivisions[k] = k < static_cast<int>(body.subdivisions.size()) ?
                                  std::max(1u, body.subdivisions[k]) : 1;
              boxes *= subdivisions[k];
              grid += (k == 0 ? "" : " x ") + std::to_string(subdivisions[k]);
            }
          // deal.II splits each square into 2 triangles, each cube into 5 tetrahedra.
          check_fits_in_memory<dim>(boxes * (dim == 1 ? 1 : dim == 2 ? 2 : 5), body, grid + " subdivisions");
          const Point<dim> lower = to_point<dim>(body.lower), upper = to_point<dim>(body.upper);
          for (int k = 0; k < dim; ++k)
            if (!(upper[k] > lower[k]))
              throw std::runtime_error("upper corner must exceed lower corner in every direction");
          if constexpr (dim == 1)
            GridGenerator::subdivided_hyper_rectangle(tria, subdivisions, lower, upper);
          else
            GridGenerator::subdivided_hyper_rectangle_with_simplices(tria, subdivisions, lower,
                                                                     upper);
        }
      else if (body.shape == "disk" || body.shape == "ball")
        {
          if (dim == 1 || (dim == 2) != (body.shape == "disk"))
            throw std::runtime_error("shape '" + body.shape + "' does not exist in dimension " +
                                     std::to_string(dim));
          if (!(body.radius > 0))
            throw std::runtime_error("radius must be positive");
          // deal.II's balanced disk has 12 squares, its ball 32 cubes; each square becomes 8
          // triangles, each cube 24 tetrahedra.
          const double coarse = dim == 2 ? 12 * 8 : 32 * 24;
          check_fits_in_memory<dim>(coarse * std::pow(2.0, dim * static_cast<double>(body.shape_refinements)), body,
                                    std::to_string(body.shape_refinements) + " shape refinements");
          if constexpr (dim > 1)
            {
              Triangulation<dim> hex;
              GridGenerator::hyper_ball_balanced(hex, to_point<dim>(body.center), body.radius);
              hex.refine_global(body.shape_refinements);
              GridGenerator::convert_hypercube_to_simplex_mesh(hex, tria);
            }
        }
      else
        throw std::runtime_error("unknown shape '" + body.shape + "'");

      // Flat geometry from here on: uniform refinement subdivides edges at their midpoints.
      tria.reset_all_manifolds();
      tria.set_all_manifold_ids(numbers::flat_manifold_id);
      tria.refine_global(body.refinements);
      GridTools::shift(to_point<dim>(body.translation), tria);
    }

    // deal.II cannot colorize simplex rectangles, so boundary ids of generated boxes follow
    // its hypercube convention by geometry: 2k on the lower face in direction k, 2k+1 upper.
    template <int dim>
    unsigned int generated_boundary_id(const BodyDescription &body, const Vec<dim> &centroid)
    {
      if (body.shape == "disk" || body.shape == "ball")
        return 0;
      const double scale = 1e-8 * (to_point<dim>(body.upper) - to_point<dim>(body.lower)).norm();
      for (int k = 0; k < dim; ++k)
        {
          const double shift = k < static_cast<int>(body.translation.size()) ? body.translation[k] : 0;
          if (std::abs(centroid[k] - body.lower[k] - shift) < scale)
            return 2 * k;
          if (std::abs(centroid[k] - body.upper[k] - shift) < scale)
            return 2 * k + 1;
        }
      return 0;
    }

    template <int dim>
    SimplexMesh<dim> extract_mesh(const BodyDescription &body, dealii::Triangulation<dim> &tria)
    {
      using namespace dealii;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->n_vertices() != dim + 1)
          throw std::runtime_error("mesh of '" + (body.file.empty() ? body.shape : body.file) +
                                   "' has non-simplex cells; only lines, triangles and "
                                   "tetrahedra are supported");

      // A linear Lagrange DoFHandler numbers exactly one unknown per vertex; Cuthill-McKee
      // keeps the Hessian's bandwidth (and the Cholesky fill-in) small.
      std::unique_ptr<FiniteElement<dim>> fe;
      if constexpr (dim == 1)
        fe = std::make_unique<FE_Q<dim>>(1);
      else
        fe = std::make_unique<FE_SimplexP<dim>>(1);
      DoFHandler<dim> dof_handler(tria);
      dof_handler.distribute_dofs(*fe);
      DoFRenumbering::Cuthill_McKee(dof_handler);

      SimplexMesh<dim> mesh;
      mesh.reference.resize(dof_handler.n_dofs() * dim);
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          typename SimplexMesh<dim>::Cell nodes;
          for (unsigned int v = 0; v <= dim; ++v)
            {
              nodes[v] = cell->vertex_dof_index(v, 0);
              for (int k = 0; k < dim; ++k)
                mesh.reference[nodes[v] * dim + k] = cell->vertex(v)[k];
            }
          mesh.cells.push_back(nodes);
          mesh.cell_material.push_back(body.shape == "file" ? cell->material_id() :
                                                              body.material_id);
        }

      // Boundary ids: from the file's physical tags, or by geometry for generated shapes.
      std::map<std::vector<unsigned int>, unsigned int> facet_ids;
      for (const auto &cell : dof_handler.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              std::vector<unsigned int> key;
              Vec<dim>                  centroid = Vec<dim>::Zero();
              for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
                {
                  key.push_back(cell->face(f)->vertex_dof_index(v, 0));
                  for (int k = 0; k < dim; ++k)
                    centroid[k] += cell->face(f)->vertex(v)[k] / cell->face(f)->n_vertices();
                }
              std::sort(key.begin(), key.end());
              facet_ids[key] = body.shape == "file" ? cell->face(f)->boundary_id() :
                                                      generated_boundary_id<dim>(body, centroid);
            }
      compute_boundary_and_bodies(mesh);
      for (unsigned int f = 0; f < mesh.boundary_facets.size(); ++f)
        {
          std::vector<unsigned int> key(mesh.boundary_facets[f].begin(), mesh.boundary_facets[f].end());
          std::sort(key.begin(), key.end());
          const auto it       = facet_ids.find(key);
          mesh.boundary_ids[f] = it == facet_ids.end() ? 0 : it->second;
        }
      return mesh;
    }

    // A facet as one cell sees it: its nodes in outward order, and in 1D, where a facet is a
    // single node, which end of the cell it is (+1 the upper, -1 the lower).
    template <int dim>
    struct OrientedFacet
    {
      std::array<unsigned int, dim> nodes;
      int                           end = 0;
    };

    // Whether two cells see the same facet with the same orientation: then they lie on the
    // same side of it.
    template <int dim>
    bool same_orientation(const OrientedFacet<dim> &first, const OrientedFacet<dim> &second)
    {
      if constexpr (dim == 1)
        return first.end == second.end;
      const auto &a = first.nodes, &b = second.nodes;
      // Segments: only the identity. Triangles: the even permutations are the rotations.
      for (int shift = 0; shift < (dim == 3 ? 3 : 1); ++shift)
        {
          bool equal = true;
          for (int k = 0; k < dim; ++k)
            equal &= a[k] == b[(k + shift) % dim];
          if (equal)
            return true;
        }
      return false;
    }

    // Appends `part` to `mesh`, offsetting node indices and body ids.
    template <int dim>
    void append_mesh(SimplexMesh<dim> &mesh, const SimplexMesh<dim> &part)
    {
      const unsigned int node_offset = mesh.n_nodes(), body_offset = mesh.n_bodies();
      mesh.reference.conservativeResize(mesh.reference.size() + part.reference.size());
      mesh.reference.tail(part.reference.size()) = part.reference;
      for (auto cell : part.cells)
        {
          for (auto &n : cell)
            n += node_offset;
          mesh.cells.push_back(cell);
        }
      mesh.cell_material.insert(mesh.cell_material.end(), part.cell_material.begin(),
                                part.cell_material.end());
      for (auto facet : part.boundary_facets)
        {
          for (auto &n : facet)
            n += node_offset;
          mesh.boundary_facets.push_back(facet);
        }
      mesh.boundary_ids.insert(mesh.boundary_ids.end(), part.boundary_ids.begin(),
                               part.boundary_ids.end());
      for (const unsigned int b : part.node_body)
        mesh.node_body.push_back(b + body_offset);
    }
  } // namespace

  template <int dim>
  unsigned int SimplexMesh<dim>::n_bodies() const
  {
    return node_body.empty() ? 0 : *std::max_element(node_body.begin(), node_body.end()) + 1;
  }

  template <int dim>
  void compute_boundary_and_bodies(SimplexMesh<dim> &mesh)
  {
    // Orient every cell positively.
    for (auto &cell : mesh.cells)
      if (simplex_measure<dim, double>(cell_nodes<dim>(mesh.reference, cell)) < 0)
        std::swap(cell[0], cell[1]);

    // A facet is on the boundary when exactly one cell has it.
    std::map<std::array<unsigned int, dim>, std::pair<int, OrientedFacet<dim>>> facets;
    for (const auto &cell : mesh.cells)
      for (int skip = 0; skip <= dim; ++skip)
        {
          // Facet opposite node `skip`, outward-oriented: the boundary of a positive simplex
          // is sum_i (-1)^i [nodes without i], so odd facets are reversed (in 1D: node 1 is
          // the upper end).
          OrientedFacet<dim> facet;
          for (int a = 0, j = 0; a <= dim; ++a)
            if (a != skip)
              facet.nodes[j++] = cell[a];
          if (skip % 2 == 1 && dim > 1)
            std::swap(facet.nodes[0], facet.nodes[1]);
          facet.end = skip == 0 ? 1 : -1;
          auto key  = facet.nodes;
          std::sort(key.begin(), key.end());
          auto &entry = facets[key];
          // Two positively oriented cells on opposite sides of a facet see it with opposite
          // orientations; the same orientation twice, or a third cell, means that cells
          // overlap (a folded or inverted element in the input; in 1D a rod folded back on
          // itself or branching).
          if (entry.first >= 2 || (entry.first == 1 && same_orientation<dim>(entry.second, facet)))
            throw std::runtime_error("the mesh has inverted (folded) elements");
          entry.first += 1;
          entry.second = facet;
        }
    mesh.boundary_facets.clear();
    for (const auto &[key, entry] : facets)
      if (entry.first == 1)
        mesh.boundary_facets.push_back(entry.second.nodes);
    mesh.boundary_ids.assign(mesh.boundary_facets.size(), 0);

    // Bodies are the connected components of the cell graph (union-find over nodes).
    std::vector<unsigned int> parent(mesh.n_nodes());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto find = [&](unsigned int i) {
      while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
      return i;
    };
    for (const auto &cell : mesh.cells)
      for (int a = 1; a <= dim; ++a)
        parent[find(cell[a])] = find(cell[0]);
    std::map<unsigned int, unsigned int> component;
    mesh.node_body.resize(mesh.n_nodes());
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      {
        const auto it = component.emplace(find(i), component.size()).first;
        mesh.node_body[i] = it->second;
      }
  }

  template <int dim>
  SimplexMesh<dim> build_mesh(const std::vector<BodyDescription> &bodies)
  {
    SimplexMesh<dim> mesh;
    mesh.reference.resize(0);
    for (const auto &body : bodies)
      {
        dealii::Triangulation<dim> tria;
        generate_body<dim>(body, tria);
        const unsigned int part = mesh.node_part.size() == 0 ? 0 : mesh.node_part.back() + 1;
        append_mesh(mesh, extract_mesh<dim>(body, tria));
        mesh.node_part.resize(mesh.n_nodes(), part);
      }
    return mesh;
  }

  template <int dim>
  SimplexMesh<dim> refine_uniformly(const SimplexMesh<dim> &mesh)
  {
    // Rebuild a deal.II triangulation from the cells and let it subdivide every edge.
    std::vector<dealii::Point<dim>> vertices(mesh.n_nodes());
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      for (int k = 0; k < dim; ++k)
        vertices[i][k] = mesh.reference[i * dim + k];
    std::vector<dealii::CellData<dim>> cells(mesh.n_cells());
    for (unsigned int c = 0; c < mesh.n_cells(); ++c)
      {
        cells[c].vertices.assign(mesh.cells[c].begin(), mesh.cells[c].end());
        cells[c].material_id = mesh.cell_material[c];
      }
    dealii::Triangulation<dim> tria;
    tria.create_triangulation(vertices, cells, dealii::SubCellData());
    BodyDescription body;
    body.shape = "file";  // keep material ids; boundary ids are restored below
    tria.refine_global(1);
    SimplexMesh<dim> fine = extract_mesh<dim>(body, tria);
    // Refinement keeps every coarse node, so each fine body contains coarse nodes, whose part
    // it inherits.
    std::map<std::vector<double>, unsigned int> part_at;
    for (unsigned int i = 0; i < mesh.n_nodes() && !mesh.node_part.empty(); ++i)
      part_at[std::vector<double>(mesh.reference.data() + i * dim, mesh.reference.data() + (i + 1) * dim)] =
        mesh.node_part[i];
    std::vector<unsigned int> part_of_body(fine.n_bodies(), 0);
    for (unsigned int i = 0; i < fine.n_nodes(); ++i)
      {
        const auto it =
          part_at.find(std::vector<double>(fine.reference.data() + i * dim, fine.reference.data() + (i + 1) * dim));
        if (it != part_at.end())
          part_of_body[fine.node_body[i]] = it->second;
      }
    fine.node_part.resize(fine.n_nodes());
    for (unsigned int i = 0; i < fine.n_nodes(); ++i)
      fine.node_part[i] = part_of_body[fine.node_body[i]];

    // A fine boundary facet inherits the id of the coarse facet whose plane contains it.
    for (unsigned int f = 0; f < fine.boundary_facets.size(); ++f)
      {
        Vec<dim> centroid = Vec<dim>::Zero();
        for (const unsigned int n : fine.boundary_facets[f])
          centroid += fine.reference_node(n) / dim;
        double best = std::numeric_limits<double>::max();
        for (unsigned int g = 0; g < mesh.boundary_facets.size(); ++g)
          {
            Vec<dim> c = Vec<dim>::Zero();
            for (const unsigned int n : mesh.boundary_facets[g])
              c += mesh.reference_node(n) / dim;
            if ((c - centroid).squaredNorm() < best)
              {
                best               = (c - centroid).squaredNorm();
                fine.boundary_ids[f] = mesh.boundary_ids[g];
              }
          }
      }
    return fine;
  }

  template <int dim>
  double min_cell_measure(const SimplexMesh<dim> &mesh, const Eigen::VectorXd &positions,
                          const bool relative)
  {
    double result = std::numeric_limits<double>::max();
    for (const auto &cell : mesh.cells)
      {
        double m = simplex_measure<dim, double>(cell_nodes<dim>(positions, cell));
        if (relative)
          m /= simplex_measure<dim, double>(cell_nodes<dim>(mesh.reference, cell));
        result = std::min(result, m);
      }
    return result;
  }

#define RITR_INSTANTIATE(dim)                                                              \
  template struct SimplexMesh<dim>;                                                        \
  template SimplexMesh<dim> build_mesh<dim>(const std::vector<BodyDescription> &);         \
  template SimplexMesh<dim> refine_uniformly<dim>(const SimplexMesh<dim> &);               \
  template void             compute_boundary_and_bodies<dim>(SimplexMesh<dim> &);          \
  template double min_cell_measure<dim>(const SimplexMesh<dim> &, const Eigen::VectorXd &, bool);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr
