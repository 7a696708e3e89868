#pragma once
// The .prm schema (deal.II ParameterHandler): declaration with documentation and defaults,
// parsing, and validation into a Scene with one-line error messages.
#include <ritr/common/input_error.h>
#include <ritr/scene/scene.h>

#include <ostream>
#include <string>

namespace ritr
{
  // Reads and validates a scene; throws InputError.
  Scene read_scene(const std::string &parameter_file);

  // Every parameter with its documentation and default, in .prm syntax.
  void print_parameters(std::ostream &out);

  constexpr unsigned int max_bodies = 8, max_materials = 8, max_dirichlet = 4, max_obstacles = 8;
} // namespace ritr
