#pragma once
// A .prm file read before deal.II parses it, for what the parser does not tell: whether it
// sets anything at all (an empty scene would run every default) and the line where each
// entry is set, so that messages can say FILE:LINE. Also folds deal.II's multi-line parser messages into one line.
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
    bool                                sets_an_entry = false;  // a `set` statement exists
  };

  // Throws InputError when `file` is a folder or cannot be read.
  SceneFile read_scene_file(const std::string &file);

  // deal.II's "Line <3> of file <f>: The entry value\n  ...\n  for the entry named ..." as
  // "f:3: The entry value ... for the entry named ...", each echoed piece shortened. A message
  // without a line that names an entry ("... for entry <epsilon r> ...", a value its
  // pattern let through but that does not convert) gets the line and path of the one entry
  // of that name `scene` sets.
  std::string fold_parser_message(const std::string &message, const std::string &file, const SceneFile &scene = {});
} // namespace ritr
