#include <ritr/adaptivity/reference_penalties.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <set>

namespace ritr
{
  namespace
  {
    // Outward unit normal and measure of a boundary facet at positions u.
    template <int dim>
    std::pair<Vec<dim>, double> facet_normal(const std::array<unsigned int, dim> &f, const Eigen::VectorXd &u)
    {
      Vec<dim> n = Vec<dim>::Zero();
      if constexpr (dim == 1)
        return {n, 1.0};
      else if constexpr (dim == 2)
        {
          const Vec<2> t = u.segment<2>(f[1] * 2) - u.segment<2>(f[0] * 2);
          n              = Vec<2>(t[1], -t[0]);
        }
      else
        n = 0.5 * (u.segment<3>(f[1] * 3) - u.segment<3>(f[0] * 3)).cross(u.segment<3>(f[2] * 3) - u.segment<3>(f[0] * 3));
      const double measure = n.norm();
      return {n / measure, measure};
    }
  } // namespace

  template <int dim>
  std::vector<SlidingConstraint<dim>> classify_sliding(const SimplexMesh<dim> &mesh, const double eps_b)
  {
    const Eigen::VectorXd &u = mesh.reference;
    std::vector<SlidingConstraint<dim>> c(mesh.n_nodes());
    std::vector<std::vector<unsigned int>> facets_of(mesh.n_nodes());
    std::vector<std::set<unsigned int>>    neighbours(mesh.n_nodes());  // along boundary edges
    for (unsigned int f = 0; f < mesh.boundary_facets.size(); ++f)
      for (int a = 0; a < dim; ++a)
        {
          const unsigned int i = mesh.boundary_facets[f][a];
          facets_of[i].push_back(f);
          for (int b = 0; b < dim; ++b)
            if (b != a)
              neighbours[i].insert(mesh.boundary_facets[f][b]);
        }
    for (unsigned int i = 0; i < mesh.n_nodes(); ++i)
      {
        if (facets_of[i].empty())
          continue;
        auto &ci  = c[i];
        ci.anchor = mesh.reference_node(i);
        ci.kind   = SlidingKind::corner;
        if constexpr (dim == 1)
          continue;  // rod ends stay put
        else
          {
            // Facet sliding: every incident facet's normal is close to the weighted normal.
            Vec<dim> normal = Vec<dim>::Zero();
            for (const unsigned int f : facets_of[i])
              {
                const auto [n, w] = facet_normal<dim>(mesh.boundary_facets[f], u);
                normal += w * n;
              }
            normal.normalize();
            bool planar = true;
            for (const unsigned int f : facets_of[i])
              planar &= 1.0 - normal.dot(facet_normal<dim>(mesh.boundary_facets[f], u).first) <= eps_b;
            if (planar)
              {
                ci.kind      = SlidingKind::facet;
                ci.direction = normal;
                continue;
              }
            // Edge sliding (3D): exactly one pair of boundary edges through i is straight.
            if constexpr (dim == 3)
              {
                const std::vector<unsigned int> ring(neighbours[i].begin(), neighbours[i].end());
                int                             straight = 0;
                Vec<dim>                        tangent  = Vec<dim>::Zero();
                for (std::size_t j = 0; j < ring.size(); ++j)
                  for (std::size_t k = j + 1; k < ring.size(); ++k)
                    {
                      const Vec<dim> tj = (mesh.reference_node(ring[j]) - ci.anchor).normalized();
                      const Vec<dim> tk = (mesh.reference_node(ring[k]) - ci.anchor).normalized();
                      if (tj.dot(tk) + 1.0 <= eps_b)
                        {
                          ++straight;
                          tangent = (tj - tk).normalized();
                        }
                    }
                if (straight == 1)
                  {
                    ci.kind      = SlidingKind::edge;
                    ci.direction = tangent;
                  }
              }
          }
      }
    return c;
  }

  template <int dim>
  double sliding_violation(const std::vector<SlidingConstraint<dim>> &c, const Eigen::VectorXd &u)
  {
    double worst = 0;
    for (unsigned int i = 0; i < c.size(); ++i)
      if (c[i].kind == SlidingKind::facet || c[i].kind == SlidingKind::edge)
        {
          const Vec<dim> r = u.template segment<dim>(i * dim) - c[i].anchor;
          const Vec<dim> &t = c[i].direction;
          worst = std::max(worst, c[i].kind == SlidingKind::facet ? std::abs(r.dot(t)) : (r - r.dot(t) * t).norm());
        }
    return worst;
  }

#define RITR_INSTANTIATE(dim)                                                                                    \
  template std::vector<SlidingConstraint<dim>> classify_sliding<dim>(const SimplexMesh<dim> &, double);          \
  template double sliding_violation<dim>(const std::vector<SlidingConstraint<dim>> &, const Eigen::VectorXd &);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr
