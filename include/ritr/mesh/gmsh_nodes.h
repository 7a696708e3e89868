#pragma once
// What deal.II's gmsh reader does not check: that every node tag is defined once (it lets a
// second definition silently replace the first).
#include <string>

namespace ritr
{
  // Throws std::runtime_error naming the file and the tag when an ASCII gmsh file (format 2
  // or 4) defines a node twice. Anything else is left to the reader.
  void check_unique_node_tags(const std::string &file);
} // namespace ritr
