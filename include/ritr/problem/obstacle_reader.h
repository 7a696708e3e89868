#pragma once
// Rigid obstacle surfaces from gmsh files: segments (2D) or triangles (3D), read with
// deal.II's GridIn as a codimension-one mesh. (.obj files are read by the contact module.)
#include <ritr/contact/rigid_obstacle.h>

#include <string>

namespace ritr
{
  // Throws std::runtime_error naming the file when it cannot be read.
  template <int dim>
  contact::RigidObstacle<dim> read_obstacle_msh(const std::string &file);
} // namespace ritr
