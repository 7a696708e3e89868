#pragma once
// A .prm file read before deal.II parses it: the checks the parser does not make (a
// directory, a scene that sets nothing) and the line where each entry is set, so that
// messages can say FILE:LINE. Also folds deal.II's multi-line parser messages into one line.
#include <map>
#include <string>

namespace ritr
{
  struct SceneFile
  {
    std::string text;
    // "Subsection/entry" (or "entry" at the top level, "Subsection" for the section itself)
    // -> the line that sets it last.
    std::map<std::string, unsigned int> lines;
  };

  // Throws InputError when `file` is not a readable file that sets at least one entry.
  SceneFile read_scene_file(const std::string &file);

  // deal.II's "Line <3> of file <f>: The entry value\n  ...\n  for the entry named ..." as
  // "f:3: The entry value ... for the entry named ...", each echoed piece shortened.
  std::string fold_parser_message(const std::string &message, const std::string &file);
} // namespace ritr
