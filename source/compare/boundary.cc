#include <ritr/compare/boundary.h>

#include <algorithm>
#include <map>

namespace ritr::compare
{
  Boundary extract_boundary(const DeformedMesh &mesh)
  {
    // Count each facet under its sorted vertex list; keep the first orientation seen.
    std::map<std::vector<unsigned int>, std::pair<std::vector<unsigned int>, unsigned int>> uses;
    for (const auto &cell : mesh.cells)
      for (std::size_t left_out = 0; left_out < cell.size(); ++left_out)
        {
          std::vector<unsigned int> facet;
          for (std::size_t i = 0; i < cell.size(); ++i)
            if (i != left_out)
              facet.push_back(cell[i]);
          std::vector<unsigned int> key = facet;
          std::sort(key.begin(), key.end());
          auto &entry = uses.try_emplace(key, facet, 0u).first->second;
          ++entry.second;
        }

    Boundary boundary{mesh.dim, mesh.points, {}};
    for (const auto &[key, entry] : uses)
      if (entry.second == 1)
        boundary.facets.push_back(entry.first);
    return boundary;
  }
} // namespace ritr::compare
