#include <ritr/mesh/gmsh_checks.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unordered_set>
#include <vector>

namespace ritr
{
  namespace
  {
    // Reads up to `section` ("$Nodes", "$Elements"); returns the format version, or 0 for a
    // file that is not ASCII gmsh or has no such section.
    double skip_to_section(std::istream &in, const std::string &section)
    {
      std::string token;
      double      version = 0;
      int         binary  = 0;
      while (in >> token && token != section)
        if (token == "$MeshFormat")
          in >> version >> binary;
      return in && binary == 0 ? version : 0;
    }

    // gmsh's element type of the linear simplex of each dimension.
    int simplex_type(const int element_dim) { return element_dim == 1 ? 1 : element_dim == 2 ? 2 : 4; }

    const char *simplex_name(const int element_dim)
    {
      return element_dim == 1 ? "segment" : element_dim == 2 ? "triangle" : "tetrahedron";
    }
  } // namespace

  void check_unique_node_tags(const std::string &file)
  {
    std::ifstream in(file);
    const double  version = skip_to_section(in, "$Nodes");
    if (version == 0)
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

  void check_unique_elements(const std::string &file, const int element_dim)
  {
    std::ifstream in(file);
    const double  version = skip_to_section(in, "$Elements");
    if (version == 0)
      return;
    // Each simplex's sorted node tags, and the element that had them first.
    std::map<std::vector<long long>, long long> first_with;
    const auto add = [&](const long long element, std::vector<long long> nodes) {
      std::sort(nodes.begin(), nodes.end());
      const auto [it, inserted] = first_with.emplace(nodes, element);
      if (!inserted)
        throw std::runtime_error("mesh file '" + file + "' has a duplicated " + simplex_name(element_dim) +
                                 ": element " + std::to_string(element) + " repeats the nodes of element " +
                                 std::to_string(it->second));
    };
    std::string line;
    std::getline(in, line);  // the end of the "$Elements" line
    const auto next_numbers = [&]() {
      std::vector<long long> numbers;
      if (std::getline(in, line) && line.rfind("$End", 0) != 0)
        {
          std::istringstream fields(line);
          for (long long n; fields >> n;)
            numbers.push_back(n);
        }
      return numbers;
    };
    if (version < 4)
      {
        // n, then "tag type n_tags tags... nodes..." per line.
        const auto header = next_numbers();
        for (long long i = 0; !header.empty() && i < header[0]; ++i)
          {
            const auto e = next_numbers();
            if (e.size() < 3 || e[2] < 0 || static_cast<std::size_t>(3 + e[2]) > e.size())
              return;  // malformed: the reader says so
            if (e[1] == simplex_type(element_dim))
              add(e[0], std::vector<long long>(e.begin() + 3 + e[2], e.end()));
          }
        return;
      }
    // Blocks of "dim entity type n", then n lines of "tag nodes...".
    const auto header = next_numbers();
    for (long long b = 0; !header.empty() && b < header[0]; ++b)
      {
        const auto block = next_numbers();
        if (block.size() < 4)
          return;
        for (long long i = 0; i < block[3]; ++i)
          {
            const auto e = next_numbers();
            if (e.empty())
              return;
            if (block[2] == simplex_type(element_dim))
              add(e[0], std::vector<long long>(e.begin() + 1, e.end()));
          }
      }
  }
} // namespace ritr
