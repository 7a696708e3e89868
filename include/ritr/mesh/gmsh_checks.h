#pragma once
// What deal.II's gmsh reader does not check, read from the file before it: that every node
// tag is defined once (it lets a second definition silently replace the first), and that no
// element repeats another's nodes (it reads the copy as an overlapping element).
#include <string>

namespace ritr
{
  // Throws std::runtime_error naming the file and the tag when an ASCII gmsh file (format 2
  // or 4) defines a node twice. Anything else is left to the reader.
  void check_unique_node_tags(const std::string &file);

  // Throws std::runtime_error naming the file and both elements when two simplices of
  // dimension `element_dim` (lines, triangles, tetrahedra) of an ASCII gmsh file (format 2
  // or 4) have the same nodes. Anything else is left to the reader.
  void check_unique_elements(const std::string &file, int element_dim);
} // namespace ritr
