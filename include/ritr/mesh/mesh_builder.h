#pragma once
// Building the simulation mesh: deal.II generates or reads each body (GridGenerator,
// GridIn for gmsh files), refines it uniformly, and numbers its nodes through a DoFHandler
// with a bandwidth-reducing renumbering; the bodies are then concatenated into one
// SimplexMesh.
#include <ritr/mesh/simplex_mesh.h>

#include <string>
#include <vector>

namespace ritr
{
  // One body of a scene, as the parameter file describes it.
  struct BodyDescription
  {
    std::string               shape = "rectangle";  // interval|rectangle|box|disk|ball|file
    std::string               file;                 // gmsh .msh, for shape = file
    std::vector<double>       lower{0, 0, 0};       // interval/rectangle/box corners
    std::vector<double>       upper{1, 1, 1};
    std::vector<unsigned int> subdivisions{1, 1, 1};
    std::vector<double>       center{0, 0, 0};      // disk/ball
    double                    radius = 1.0;
    // Refinements of the quadrilateral/hexahedral disk or ball before it is split into
    // simplices (they follow the round boundary), and uniform simplex refinements after.
    unsigned int              shape_refinements = 2;
    unsigned int              refinements       = 0;
    std::vector<double>       translation{0, 0, 0};
    unsigned int              material_id = 0;
  };

  template <int dim>
  SimplexMesh<dim> build_mesh(const std::vector<BodyDescription> &bodies);

  // Uniform refinement by edge subdivision (1 -> 2^dim simplices), for convergence ladders.
  template <int dim>
  SimplexMesh<dim> refine_uniformly(const SimplexMesh<dim> &mesh);

  // Boundary facets, orientation and bodies recomputed from cells and node positions.
  template <int dim>
  void compute_boundary_and_bodies(SimplexMesh<dim> &mesh);
} // namespace ritr
