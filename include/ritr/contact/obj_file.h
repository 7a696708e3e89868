#pragma once
// Rigid obstacle surfaces from Wavefront .obj files: 'v' vertices, 'l' polylines (2D) or 'f'
// triangles (3D); other lines are ignored.
#include <ritr/contact/rigid_obstacle.h>

#include <string>

namespace ritr::contact
{
  // Throws std::runtime_error "FILE:LINE: what is wrong" on malformed input: a vertex with
  // fewer than dim coordinates or one that is not a finite number, an index that is not an
  // integer or names no vertex defined before it, a face that is not a triangle, a segment of
  // zero length or a triangle of zero area. Throws naming the file when it cannot be read or
  // holds no segment (2D) or triangle (3D).
  template <int dim>
  RigidObstacle<dim> read_obj(const std::string &file);
} // namespace ritr::contact
