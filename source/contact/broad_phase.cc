#include <ritr/contact/broad_phase.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace ritr::contact
{
  template <int dim>
  int stencil_vertices(const CollisionSurface<dim> &surface, const Candidate &c,
                       std::array<int, 4> &v)
  {
    v = {{-1, -1, -1, -1}};
    switch (c.kind)
      {
        case ContactKind::vertex_vertex:
          v[0] = c.first, v[1] = c.second;
          return 2;
        case ContactKind::point_edge:
          v[0] = c.first, v[1] = surface.edges[c.second][0], v[2] = surface.edges[c.second][1];
          return 3;
        case ContactKind::point_triangle:
          v[0] = c.first;
          for (int i = 0; i < 3; ++i)
            v[1 + i] = surface.faces[c.second][i];
          return 4;
        case ContactKind::edge_edge:
          v[0] = surface.edges[c.first][0], v[1] = surface.edges[c.first][1];
          v[2] = surface.edges[c.second][0], v[3] = surface.edges[c.second][1];
          return 4;
      }
    return 0;
  }

  namespace
  {
    // Boxes of the vertices, each inflated by half the requested inflation so that two
    // primitives closer than `inflation` have overlapping boxes (per-axis gaps are bounded
    // by the Euclidean distance).
    template <int dim>
    std::vector<Aabb<dim>> vertex_boxes(const Eigen::MatrixXd &V0, const Eigen::MatrixXd *V1,
                                        const double inflation)
    {
      const int              n = static_cast<int>(V0.rows());
      std::vector<Aabb<dim>> boxes(n);
      const double           r = 0.5 * inflation;
      tbb::parallel_for(tbb::blocked_range<int>(0, n, 4096), [&](const auto &range) {
        for (int i = range.begin(); i != range.end(); ++i)
          {
            Eigen::Matrix<double, dim, 1> a = V0.row(i).transpose();
            boxes[i].min = a, boxes[i].max = a;
            if (V1)
              {
                const Eigen::Matrix<double, dim, 1> b = V1->row(i).transpose();
                boxes[i].min = boxes[i].min.cwiseMin(b);
                boxes[i].max = boxes[i].max.cwiseMax(b);
              }
            boxes[i].inflate(r);
          }
      });
      return boxes;
    }

    template <int N, int dim>
    std::vector<Aabb<dim>> primitive_boxes(const std::vector<std::array<int, N>> &prims,
                                           const std::vector<Aabb<dim>>          &vboxes)
    {
      std::vector<Aabb<dim>> boxes(prims.size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, prims.size(), 4096),
                        [&](const auto &range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i)
                            for (int k = 0; k < N; ++k)
                              boxes[i].extend(vboxes[prims[i][k]]);
                        });
      return boxes;
    }

    template <int dim>
    std::vector<Candidate> find_candidates_impl(const CollisionSurface<dim> &surface,
                                                const Eigen::MatrixXd &V0,
                                                const Eigen::MatrixXd *V1,
                                                const double           inflation)
    {
      if (V0.rows() != surface.n_vertices || V0.cols() != dim ||
          (V1 && (V1->rows() != V0.rows() || V1->cols() != dim)))
        throw std::invalid_argument("find_candidates: position matrix has the wrong shape");

      const auto vboxes = vertex_boxes<dim>(V0, V1, inflation);
      tbb::enumerable_thread_specific<std::vector<Candidate>> local;

      // Queries `count` primitives against `tree`; accept(i, j, out) filters and stores.
      const auto run = [&](const int count, const auto &query_box, const AabbTree<dim> &tree,
                           const auto &accept) {
        tbb::parallel_for(tbb::blocked_range<int>(0, count, 256), [&](const auto &range) {
          auto &out = local.local();
          for (int i = range.begin(); i != range.end(); ++i)
            tree.for_each_overlap(query_box(i), [&](const int j) { accept(i, j, out); });
        });
      };
      const auto obstacle = [&](const int v) { return surface.vertex_is_obstacle(v); };

      if constexpr (dim == 1)
        {
          const AabbTree<1> tree(vboxes);
          run(surface.n_vertices, [&](const int i) { return vboxes[i]; }, tree,
              [&](const int a, const int b, std::vector<Candidate> &out) {
                if (b <= a || (obstacle(a) && obstacle(b)))
                  return;
                // The body vertex first: its weight is used.
                if (obstacle(a))
                  out.push_back({ContactKind::vertex_vertex, b, a});
                else
                  out.push_back({ContactKind::vertex_vertex, a, b});
              });
        }
      else
        {
          const auto    eboxes = primitive_boxes<2, dim>(surface.edges, vboxes);
          const AabbTree<dim> etree(eboxes);
          if constexpr (dim == 2)
            {
              run(surface.n_vertices, [&](const int i) { return vboxes[i]; }, etree,
                  [&](const int v, const int e, std::vector<Candidate> &out) {
                    const auto &ed = surface.edges[e];
                    if (v == ed[0] || v == ed[1] || (obstacle(v) && surface.edge_is_obstacle(e)))
                      return;
                    out.push_back({ContactKind::point_edge, v, e});
                  });
            }
          else
            {
              const auto          fboxes = primitive_boxes<3, 3>(surface.faces, vboxes);
              const AabbTree<3>   ftree(fboxes);
              run(surface.n_vertices, [&](const int i) { return vboxes[i]; }, ftree,
                  [&](const int v, const int f, std::vector<Candidate> &out) {
                    const auto &fa = surface.faces[f];
                    if (v == fa[0] || v == fa[1] || v == fa[2] ||
                        (obstacle(v) && surface.face_is_obstacle(f)))
                      return;
                    out.push_back({ContactKind::point_triangle, v, f});
                  });
              run(static_cast<int>(surface.edges.size()), [&](const int i) { return eboxes[i]; },
                  etree, [&](const int a, const int b, std::vector<Candidate> &out) {
                    if (b <= a)
                      return;
                    const auto &ea = surface.edges[a], &eb = surface.edges[b];
                    if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1])
                      return;
                    const bool oa = surface.edge_is_obstacle(a), ob = surface.edge_is_obstacle(b);
                    if (oa && ob)
                      return;
                    if (oa)
                      out.push_back({ContactKind::edge_edge, b, a});
                    else
                      out.push_back({ContactKind::edge_edge, a, b});
                  });
            }
        }

      std::size_t total = 0;
      for (const auto &l : local)
        total += l.size();
      std::vector<Candidate> result;
      result.reserve(total);
      for (const auto &l : local)
        result.insert(result.end(), l.begin(), l.end());
      // Thread scheduling is not deterministic; the order of the result must be.
      std::sort(result.begin(), result.end());
      return result;
    }
  } // namespace

  template <int dim>
  std::vector<Candidate> find_candidates(const CollisionSurface<dim> &surface,
                                         const Eigen::MatrixXd &V, const double inflation)
  {
    return find_candidates_impl<dim>(surface, V, nullptr, inflation);
  }

  template <int dim>
  std::vector<Candidate> find_candidates(const CollisionSurface<dim> &surface,
                                         const Eigen::MatrixXd &V0, const Eigen::MatrixXd &V1,
                                         const double inflation)
  {
    return find_candidates_impl<dim>(surface, V0, &V1, inflation);
  }

#define RITR_INSTANTIATE(dim)                                                                    \
  template int stencil_vertices<dim>(const CollisionSurface<dim> &, const Candidate &,        \
                                     std::array<int, 4> &);                                    \
  template std::vector<Candidate> find_candidates<dim>(const CollisionSurface<dim> &,         \
                                                       const Eigen::MatrixXd &, double);      \
  template std::vector<Candidate> find_candidates<dim>(                                        \
    const CollisionSurface<dim> &, const Eigen::MatrixXd &, const Eigen::MatrixXd &, double);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE
} // namespace ritr::contact
