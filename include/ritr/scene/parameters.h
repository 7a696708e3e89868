#pragma once
// The .prm schema (deal.II ParameterHandler): declaration with documentation and defaults,
// parsing, and validation into a Scene with one-line error messages.
#include <ritr/common/input_error.h>
#include <ritr/scene/scene.h>

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace ritr
{
  // Reads and validates a scene; throws InputError.
  Scene read_scene(const std::string &parameter_file);

  // Every parameter with its documentation and default, in .prm syntax.
  void print_parameters(std::ostream &out);

  // ("Section/entry", value) of every `set` line of a .prm listing (one value per line, as
  // print_parameters writes it), in the listing's order.
  std::vector<std::pair<std::string, std::string>> listing_entries(const std::string &listing);

  // Whether the entry "Section/entry" leaves a run the same run when it changes (where the
  // outputs go, thread counts, the end time, the Newton cap, which decides only where a run
  // stops): Scene::parameter_listing leaves these out, and a checkpoint's listing is compared
  // without them, so that one written by a ritr that still listed them resumes.
  bool leaves_the_run_unchanged(const std::string &entry);

  constexpr unsigned int max_bodies = 8, max_materials = 8, max_dirichlet = 4, max_obstacles = 8;
} // namespace ritr
