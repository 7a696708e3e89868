#pragma once
// Exact moments of a candidate triangle's barycentric functions over its overlap with one
// old triangle (2D), for the L2 transfer integrated on the intersection of the two meshes:
//
//   m_aj = int_{K cap Q} lambda_a^K(X) f_j(X) dX,     f_j(X) = F_j . X + f0_j affine,
//
// with K the candidate triangle (its vertices of scalar type S, so that dual numbers carry
// derivatives in K's node coordinates) and Q an old triangle given by its affine barycentric
// map mu(X) = G X + g. Both factors are affine, so the overlap polygon's area, first and second
// moments (summed over a fan of triangles) integrate the product exactly.
//
// K is clipped by Q's three half-planes mu_b >= 0 (Sutherland-Hodgman), so the polygon's
// vertices are K's own vertices or crossings of K's edges with Q's lines, and move with K.
// Meshes that coincide in places are the rule, not the exception (every step's first
// candidate is the old mesh; boundary nodes slide along old boundary edges), so points that
// lie on a line are decided by simulation of simplicity: the old mesh is taken as shifted by
// an infinitesimal -delta d (d a fixed direction), and each polygon vertex carries, beside its
// position, its first-order motion in delta. Every candidate cell thus sees the same
// infinitesimally shifted old mesh: the overlap polygons of neighbouring old cells never
// share area, and the derivatives are those of one consistent branch (the integral is C1
// across such configurations; only its second derivatives jump there). A barycentric value
// within `tie` of zero counts as zero (round-off of points on a line).
#include <ritr/common/second_order_dual.h>
#include <ritr/transfer/old_mesh_locator.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace ritr::transfer
{
  template <typename S>
  using Point2 = std::array<S, 2>;

  // The direction d of the symbolic shift: generic (1 radian, no angle of a regular polygon),
  // so that no mesh line is parallel to it; should one be, the perpendicular decides.
  inline constexpr std::array<double, 2> symbolic_shift{0.5403023058681398, 0.8414709848078965};

  // lambda_a(X) = c_a + e_a . X for a positively oriented triangle P.
  template <typename S>
  struct TriangleBarycentric
  {
    std::array<S, 3> c, ex, ey;

    explicit TriangleBarycentric(const std::array<Point2<S>, 3> &P)
    {
      const S det = (P[1][0] - P[0][0]) * (P[2][1] - P[0][1]) - (P[1][1] - P[0][1]) * (P[2][0] - P[0][0]);
      for (int a = 0; a < 3; ++a)
        {
          const Point2<S> &p1 = P[(a + 1) % 3], &p2 = P[(a + 2) % 3];
          const S          vx = p2[0] - p1[0], vy = p2[1] - p1[1];
          ex[a] = -vy / det;
          ey[a] = vx / det;
          c[a]  = (vy * p1[0] - vx * p1[1]) / det;
        }
    }

    S operator()(const int a, const Point2<S> &X) const { return c[a] + ex[a] * X[0] + ey[a] * X[1]; }
  };

  // Geometric moments of a region: its area, int X and int X X^T, in coordinates about a
  // fixed origin (the candidate's first vertex: the moments of a sliver then keep their digits).
  template <typename S>
  struct RegionMoments
  {
    S area = 0.0, x = 0.0, y = 0.0, xx = 0.0, xy = 0.0, yy = 0.0;
  };

  // Adds the moments of triangle (p0, p1, p2), given about the origin (signed by orientation).
  template <typename S>
  void add_triangle_geometry(const Point2<S> &p0, const Point2<S> &p1, const Point2<S> &p2, RegionMoments<S> &m)
  {
    const S area = 0.5 * ((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]));
    const S sx = p0[0] + p1[0] + p2[0], sy = p0[1] + p1[1] + p2[1];
    // int X_i X_j over a triangle = area / 12 (sum_v v_i v_j + s_i s_j).
    const S a12 = area / 12.0;
    m.area += area;
    m.x += area * sx / 3.0;
    m.y += area * sy / 3.0;
    m.xx += a12 * (p0[0] * p0[0] + p1[0] * p1[0] + p2[0] * p2[0] + sx * sx);
    m.xy += a12 * (p0[0] * p0[1] + p1[0] * p1[1] + p2[0] * p2[1] + sx * sy);
    m.yy += a12 * (p0[1] * p0[1] + p1[1] * p1[1] + p2[1] * p2[1] + sy * sy);
  }

  // Adds m_aj = int lambda_a f_j over a region with moments `g` (about `origin`) to `moments`:
  // both factors are affine, so the region's first and second moments are all it takes.
  template <typename S, int M>
  void add_moments(const RegionMoments<S> &g, const Point2<double> &origin, const TriangleBarycentric<S> &lambda,
                   const std::array<std::array<double, 3>, M> &F, std::array<std::array<S, M>, 3> &moments)
  {
    // lambda_a about the origin: c_a + e_a . X'.
    std::array<S, 3> c;
    for (int a = 0; a < 3; ++a)
      c[a] = lambda.c[a] + lambda.ex[a] * origin[0] + lambda.ey[a] * origin[1];
    for (int j = 0; j < M; ++j)
      {
        // f_j about the origin: F_j . X' + f0, X' = X - origin.
        const double fx = F[j][0], fy = F[j][1], f0 = F[j][2] + fx * origin[0] + fy * origin[1];
        const S      i1 = fx * g.x + fy * g.y + f0 * g.area;   // int f_j
        const S      ix = fx * g.xx + fy * g.xy + f0 * g.x;    // int X'_0 f_j
        const S      iy = fx * g.xy + fy * g.yy + f0 * g.y;    // int X'_1 f_j
        for (int a = 0; a < 3; ++a)
          moments[a][j] += c[a] * i1 + lambda.ex[a] * ix + lambda.ey[a] * iy;
      }
  }

  // K's vertices about the origin.
  template <typename S>
  std::array<Point2<S>, 3> about(const std::array<Point2<S>, 3> &K, const Point2<double> &origin)
  {
    std::array<Point2<S>, 3> local;
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 2; ++k)
        local[a][k] = K[a][k] - origin[k];
    return local;
  }

  // Adds int_K lambda_a f_j over the whole candidate K.
  template <typename S, int M>
  void add_triangle_moments(const std::array<Point2<S>, 3> &K, const TriangleBarycentric<S> &lambda,
                            const std::array<std::array<double, 3>, M> &F, std::array<std::array<S, M>, 3> &moments)
  {
    const Point2<double>     origin{value_of(K[0][0]), value_of(K[0][1])};
    const auto               local = about(K, origin);
    RegionMoments<S>         g;
    add_triangle_geometry(local[0], local[1], local[2], g);
    add_moments<S, M>(g, origin, lambda, F, moments);
  }

  // The overlap polygon of K and Q: a proper convex clip leaves at most 6 vertices, but with
  // points decided on a line each pass may add one vertex per edge (3, 4, 6, 9); none are merged.
  template <typename S>
  struct OverlapPolygon
  {
    struct Vertex
    {
      // Unset: a clip fills only the vertices it makes, and zeroing 9 dual vertices cost
      // more than the arithmetic of a small overlap.
      Point2<S>      X{unset<S>(), unset<S>()};
      Point2<double> shift{0.0, 0.0};  // dX / d delta of the symbolic shift
    };
    static constexpr int          capacity = 9;
    std::array<Vertex, capacity> vertices;
    int                           size = 0;  // < 3: no overlap
  };

  // K clipped by Q's half-planes mu_b >= 0.
  template <typename S>
  OverlapPolygon<S> clip(const std::array<Point2<S>, 3> &K, const AffineBarycentric<2> &Q, const double tie = 1e-13)
  {
    const double dx = symbolic_shift[0], dy = symbolic_shift[1];
    constexpr int capacity = OverlapPolygon<S>::capacity;
    using Vertex           = typename OverlapPolygon<S>::Vertex;
    // The passes alternate between the result's vertices and a scratch buffer (copying a dual
    // vertex moves 86 numbers).
    OverlapPolygon<S>            result;
    std::array<Vertex, capacity> scratch;
    int                          n = 3;
    for (int i = 0; i < 3; ++i)
      result.vertices[i].X = K[i];
    int b = 0;
    for (; b < 3 && n >= 3; ++b)
      {
        auto &polygon = b % 2 == 0 ? result.vertices : scratch;
        auto &clipped = b % 2 == 0 ? scratch : result.vertices;
        const double gx = Q.gradient(b, 0), gy = Q.gradient(b, 1), g0 = Q.offset[b];
        // mu_b at each vertex of the shifted configuration, v + delta e (v in plain arithmetic
        // for the decisions; as a dual number only where a crossing needs it).
        std::array<double, capacity> v, e;
        std::array<bool, capacity>   inside, on_line;
        for (int i = 0; i < n; ++i)
          {
            v[i]       = gx * value_of(polygon[i].X[0]) + gy * value_of(polygon[i].X[1]) + g0;
            e[i]       = gx * (polygon[i].shift[0] + dx) + gy * (polygon[i].shift[1] + dy);
            on_line[i] = std::abs(v[i]) <= tie;
            inside[i]  = on_line[i] ? (e[i] != 0 ? e[i] > 0 : gy * dx - gx * dy > 0) : v[i] > 0;
          }
        const auto mu = [&](const int i) {
          const S a = gx * polygon[i].X[0] + gy * polygon[i].X[1] + g0;
          return on_line[i] ? S(a - v[i]) : a;  // on the line: exactly zero, derivatives kept
        };
        int m = 0;
        for (int i = 0; i < n; ++i)
          {
            const int j = (i + 1) % n;
            if (inside[i])
              clipped[m++] = polygon[i];
            if (inside[i] == inside[j])
              continue;
            const double ai = on_line[i] ? 0.0 : v[i], aj = on_line[j] ? 0.0 : v[j];
            const S      a_i = mu(i), a_j = mu(j);
            Vertex      &out = clipped[m++];
            if (ai == aj)
              {
                // Both on the line, apart only by delta (shift_j - shift_i): the shifted line
                // cuts the edge at t = e_i / (e_i - e_j). As delta -> 0 the edge shrinks like
                // delta while dt/du grows like 1/delta; their product stays, as tau below.
                const double t   = e[i] / (e[i] - e[j]);
                const S      tau = (a_j * e[i] - a_i * e[j]) / ((e[i] - e[j]) * (e[i] - e[j]));
                for (int k = 0; k < 2; ++k)
                  {
                    const double apart = polygon[j].shift[k] - polygon[i].shift[k];
                    out.X[k]     = polygon[i].X[k] + t * (polygon[j].X[k] - polygon[i].X[k]) + tau * apart;
                    out.shift[k] = polygon[i].shift[k] + t * apart;
                  }
                continue;
              }
            const S      t     = a_i / (a_i - a_j);
            const double t0    = value_of(t);
            const double shift = (ai * e[j] - aj * e[i]) / ((ai - aj) * (ai - aj));  // dt / d delta
            for (int k = 0; k < 2; ++k)
              {
                out.X[k]     = polygon[i].X[k] + t * (polygon[j].X[k] - polygon[i].X[k]);
                out.shift[k] = polygon[i].shift[k] + t0 * (polygon[j].shift[k] - polygon[i].shift[k]) +
                               shift * (value_of(polygon[j].X[k]) - value_of(polygon[i].X[k]));
              }
          }
        n = m;
      }
    if (b % 2 == 1)  // the last pass wrote the scratch buffer
      std::copy(scratch.begin(), scratch.begin() + n, result.vertices.begin());
    result.size = n;
    return result;
  }

  // Adds m_aj (a < 3, j < M) of candidate K over old triangle Q to `moments`; f_j(X) =
  // F[j][0] X_0 + F[j][1] X_1 + F[j][2]. Adds nothing without overlap.
  template <typename S, int M>
  void add_overlap_moments(const std::array<Point2<S>, 3> &K, const TriangleBarycentric<S> &lambda,
                        const AffineBarycentric<2> &Q, const std::array<std::array<double, 3>, M> &F,
                        std::array<std::array<S, M>, 3> &moments)
  {
    OverlapPolygon<S> polygon = clip(K, Q);
    if (polygon.size < 3)
      return;
    const Point2<double> origin{value_of(K[0][0]), value_of(K[0][1])};
    for (int i = 0; i < polygon.size; ++i)  // about the origin, in place (a constant moves values only)
      for (int k = 0; k < 2; ++k)
        polygon.vertices[i].X[k] -= origin[k];
    RegionMoments<S> g;
    for (int i = 1; i + 1 < polygon.size; ++i)
      add_triangle_geometry(polygon.vertices[0].X, polygon.vertices[i].X, polygon.vertices[i + 1].X, g);
    add_moments<S, M>(g, origin, lambda, F, moments);
  }
} // namespace ritr::transfer
