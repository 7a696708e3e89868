#include <ritr/mesh/gmsh_nodes.h>

#include <fstream>
#include <limits>
#include <stdexcept>
#include <unordered_set>

namespace ritr
{
  void check_unique_node_tags(const std::string &file)
  {
    std::ifstream in(file);
    std::string   token;
    double        version = 0;
    int           binary  = 0;
    while (in >> token && token != "$Nodes")
      if (token == "$MeshFormat")
        in >> version >> binary;
    if (!in || binary != 0)
      return;

    std::unordered_set<long long> tags;
    const auto                    add = [&](const long long tag) {
      if (!tags.insert(tag).second)
        throw std::runtime_error("mesh file '" + file + "' defines node " + std::to_string(tag) + " twice");
    };
    const auto skip_lines = [&](const long long n) {
      for (long long i = 0; i <= n && in; ++i)  // the rest of the current line, then n lines
        in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    };
    if (version < 4)
      {
        // n, then "tag x y z" per line.
        long long n = 0;
        in >> n;
        for (long long i = 0; i < n && in; ++i)
          {
            long long tag = 0;
            if (in >> tag)
              add(tag);
            skip_lines(0);
          }
        return;
      }
    // Blocks of "dim entity parametric n", n tags, then n coordinate lines.
    long long blocks = 0, n_nodes = 0, min_tag = 0, max_tag = 0;
    in >> blocks >> n_nodes >> min_tag >> max_tag;
    for (long long b = 0; b < blocks && in; ++b)
      {
        long long entity_dim = 0, entity = 0, parametric = 0, n = 0;
        in >> entity_dim >> entity >> parametric >> n;
        for (long long i = 0; i < n && in; ++i)
          {
            long long tag = 0;
            if (in >> tag)
              add(tag);
          }
        skip_lines(n);
      }
  }
} // namespace ritr
