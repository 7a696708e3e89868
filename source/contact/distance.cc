#include <ritr/contact/distance.h>

#include <cmath>
#include <stdexcept>

namespace ritr::contact
{
  namespace
  {
    template <int dim>
    using Vec = Eigen::Matrix<double, dim, 1>;

    template <int dim>
    Vec<dim> point(const StencilVector<dim> &x, const int i)
    {
      return x.template segment<dim>(i * dim);
    }

    // a b - c d with one rounding (Kahan's algorithm with fused multiply-add).
    inline double diff_of_products(const double a, const double b, const double c, const double d)
    {
      const double w = c * d;
      const double e = std::fma(-c, d, w);
      const double f = std::fma(a, b, -w);
      return f + e;
    }

    // Cross product accurate to a few ulps of the RESULT even for nearly parallel inputs,
    // where the naive one loses all digits. The closest-point parameters of nearly parallel
    // edges / thin triangles are ratios of such small cross products.
    inline Vec<3> accurate_cross(const Vec<3> &a, const Vec<3> &b)
    {
      return {diff_of_products(a[1], b[2], a[2], b[1]), diff_of_products(a[2], b[0], a[0], b[2]),
              diff_of_products(a[0], b[1], a[1], b[0])};
    }

    // Barycentric coordinates (u, v) of the projection of t0 + w onto the plane t0 + span(e1,
    // e2), via the identities (e1 x e2).(w x e2) = |e2|^2 e1.w - (e1.e2) e2.w etc., which avoid
    // the cancellation of the Gram-determinant form. det = |e1 x e2|^2.
    inline Eigen::Vector2d plane_parameters(const Vec<3> &e1, const Vec<3> &e2, const Vec<3> &w,
                                            const Vec<3> &n, const double det)
    {
      return {n.dot(accurate_cross(w, e2)) / det, n.dot(accurate_cross(e1, w)) / det};
    }

    // Parameters (s, t) of the closest points a0 + s ea, b0 + t eb of two lines (w = a0 -
    // b0, n = ea x eb, det = |n|^2).
    inline Eigen::Vector2d line_parameters(const Vec<3> &ea, const Vec<3> &eb, const Vec<3> &w,
                                           const Vec<3> &n, const double det)
    {
      return {n.dot(accurate_cross(eb, w)) / det, n.dot(accurate_cross(ea, w)) / det};
    }

    DistanceClass point_point(const int a, const int b)
    {
      return {DistanceType::point_point, {{a, b, -1, -1}}};
    }

    // Point p (slot sp) against segment a-b (slots sa, sb); also returns the squared
    // distance so that callers can take minima over several segments.
    template <int dim>
    DistanceClass classify_point_segment(const Vec<dim> &p, const Vec<dim> &a, const Vec<dim> &b,
                                         const int sp, const int sa, const int sb,
                                         double &dist_sqr)
    {
      const Vec<dim> e  = b - a;
      const double   ee = e.squaredNorm();
      const double   t  = ee > 0.0 ? (p - a).dot(e) / ee : 0.0;
      if (t <= 0.0)
        {
          dist_sqr = (p - a).squaredNorm();
          return point_point(sp, sa);
        }
      if (t >= 1.0)
        {
          dist_sqr = (p - b).squaredNorm();
          return point_point(sp, sb);
        }
      dist_sqr = (p - a - t * e).squaredNorm();
      return {DistanceType::point_line, {{sp, sa, sb, -1}}};
    }

    // A point against a segment, with their stencil slots (see classify_point_segment).
    struct PointSegment
    {
      const Vec<3> &p, &a, &b;
      int           sp, sa, sb;
    };

    // The class of the closest of several point-segment pairs (the first one on ties).
    DistanceClass closest_point_segment(std::initializer_list<PointSegment> pairs)
    {
      DistanceClass best;
      double        best_d = 0.0;
      bool          first  = true;
      for (const PointSegment &q : pairs)
        {
          double              d   = 0.0;
          const DistanceClass cls = classify_point_segment<3>(q.p, q.a, q.b, q.sp, q.sa, q.sb, d);
          if (first || d < best_d)
            best = cls, best_d = d;
          first = false;
        }
      return best;
    }

    DistanceClass classify_point_triangle(const Vec<3> &p, const Vec<3> &t0, const Vec<3> &t1,
                                          const Vec<3> &t2)
    {
      const Vec<3> e1 = t1 - t0, e2 = t2 - t0;
      const Vec<3> n   = accurate_cross(e1, e2);
      const double det = n.squaredNorm();
      if (det > parallel_threshold * e1.squaredNorm() * e2.squaredNorm())
        {
          // Barycentric coordinates of the projection onto the plane. The squared distance
          // is convex in them, so if the projection is inside it is the minimiser,
          // otherwise the minimum is on the boundary.
          const Eigen::Vector2d uv = plane_parameters(e1, e2, p - t0, n, det);
          const double          u = uv[0], v = uv[1];
          if (u >= 0.0 && v >= 0.0 && u + v <= 1.0)
            return {DistanceType::point_plane, {{0, 1, 2, 3}}};
        }
      return closest_point_segment(
        {{p, t0, t1, 0, 1, 2}, {p, t1, t2, 0, 2, 3}, {p, t2, t0, 0, 3, 1}});
    }

    DistanceClass classify_edge_edge(const Vec<3> &a0, const Vec<3> &a1, const Vec<3> &b0,
                                     const Vec<3> &b1)
    {
      const Vec<3> ea = a1 - a0, eb = b1 - b0;
      const Vec<3> n   = accurate_cross(ea, eb);
      const double det = n.squaredNorm(); // = |ea|^2 |eb|^2 - (ea.eb)^2 without cancellation
      if (det > parallel_threshold * ea.squaredNorm() * eb.squaredNorm())
        {
          const Eigen::Vector2d st = line_parameters(ea, eb, a0 - b0, n, det);
          const double          s = st[0], t = st[1];
          // |a0 + s ea - b0 - t eb|^2 is convex in (s, t): an interior stationary point is
          // the minimiser; otherwise the minimum is on the boundary of the unit square.
          if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)
            return {DistanceType::line_line, {{0, 1, 2, 3}}};
        }
      return closest_point_segment({{a0, b0, b1, 0, 2, 3},
                                    {a1, b0, b1, 1, 2, 3},
                                    {b0, a0, a1, 2, 0, 1},
                                    {b1, a0, a1, 3, 0, 1}});
    }
  } // namespace

  template <int dim>
  DistanceClass classify(const ContactKind kind, const StencilVector<dim> &x)
  {
    if constexpr (dim == 1)
      {
        if (kind == ContactKind::vertex_vertex)
          return point_point(0, 1);
      }
    else if constexpr (dim == 2)
      {
        if (kind == ContactKind::point_edge)
          {
            double d;
            return classify_point_segment<2>(point<2>(x, 0), point<2>(x, 1), point<2>(x, 2), 0,
                                             1, 2, d);
          }
      }
    else
      {
        if (kind == ContactKind::point_triangle)
          return classify_point_triangle(point<3>(x, 0), point<3>(x, 1), point<3>(x, 2),
                                         point<3>(x, 3));
        if (kind == ContactKind::edge_edge)
          return classify_edge_edge(point<3>(x, 0), point<3>(x, 1), point<3>(x, 2),
                                    point<3>(x, 3));
      }
    throw std::invalid_argument("contact kind not available in this dimension");
  }

  template <int dim>
  double distance_sqr(const ContactKind kind, const StencilVector<dim> &x)
  {
    const DistanceClass cls = classify<dim>(kind, x);
    if constexpr (dim == 3)
      if (cls.type == DistanceType::line_line)
        {
          // The line-line formula divides by |ea x eb|^2, whose direction has relative error
          // ~eps / sin(angle) for nearly parallel edges; explicit closest points only err
          // along the flat valley of the distance, so the value stays accurate.
          const Eigen::Vector2d st = closest_point_parameters<3>(cls, x);
          const Vec<3> a0 = point<3>(x, 0), b0 = point<3>(x, 2);
          return (a0 + st[0] * (point<3>(x, 1) - a0) - b0 - st[1] * (point<3>(x, 3) - b0))
            .squaredNorm();
        }
    return typed_distance_sqr<dim, double>(cls, to_kernel_points<dim>(x));
  }

  template <int dim>
  double distance_sqr(const ContactKind kind, const StencilVector<dim> &x,
                      StencilVector<dim> &grad, StencilMatrix<dim> &hess)
  {
    using Dual   = SecondOrderDual<stencil_dofs<dim>>;
    const Dual d = typed_distance_sqr<dim, Dual>(classify<dim>(kind, x), to_dual_points<dim>(x));
    grad         = d.grad;
    hess         = d.hess;
    return d.value;
  }

  template <int dim>
  Eigen::Vector2d closest_point_parameters(const DistanceClass &cls, const StencilVector<dim> &x)
  {
    const auto &s = cls.slots;
    switch (cls.type)
      {
        case DistanceType::point_point:
          break;
        case DistanceType::point_line:
          if constexpr (dim >= 2)
            {
              const Vec<dim> e = point<dim>(x, s[2]) - point<dim>(x, s[1]);
              const double   t = (point<dim>(x, s[0]) - point<dim>(x, s[1])).dot(e) / e.squaredNorm();
              return {t, 0.0};
            }
          break;
        case DistanceType::point_plane:
          if constexpr (dim == 3)
            {
              const Vec<3> t0 = point<3>(x, s[1]);
              const Vec<3> e1 = point<3>(x, s[2]) - t0, e2 = point<3>(x, s[3]) - t0;
              const Vec<3> n  = accurate_cross(e1, e2);
              return plane_parameters(e1, e2, point<3>(x, s[0]) - t0, n, n.squaredNorm());
            }
          break;
        case DistanceType::line_line:
          if constexpr (dim == 3)
            {
              const Vec<3> a0 = point<3>(x, s[0]), b0 = point<3>(x, s[2]);
              const Vec<3> ea = point<3>(x, s[1]) - a0, eb = point<3>(x, s[3]) - b0;
              const Vec<3> n  = accurate_cross(ea, eb);
              return line_parameters(ea, eb, a0 - b0, n, n.squaredNorm());
            }
          break;
      }
    return {0.0, 0.0};
  }

  template <int dim>
  double point_point_distance_sqr(const Eigen::Matrix<double, dim, 1> &a,
                                  const Eigen::Matrix<double, dim, 1> &b)
  {
    return (a - b).squaredNorm();
  }

  template <int dim>
  double point_edge_distance_sqr(const Eigen::Matrix<double, dim, 1> &p,
                                 const Eigen::Matrix<double, dim, 1> &e0,
                                 const Eigen::Matrix<double, dim, 1> &e1)
  {
    double d;
    classify_point_segment<dim>(p, e0, e1, 0, 1, 2, d);
    return d;
  }

  double point_triangle_distance_sqr(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                     const Eigen::Vector3d &t1, const Eigen::Vector3d &t2)
  {
    return distance_sqr<3>(ContactKind::point_triangle, make_stencil<3>({p, t0, t1, t2}));
  }

  double edge_edge_distance_sqr(const Eigen::Vector3d &ea0, const Eigen::Vector3d &ea1,
                                const Eigen::Vector3d &eb0, const Eigen::Vector3d &eb1)
  {
    return distance_sqr<3>(ContactKind::edge_edge, make_stencil<3>({ea0, ea1, eb0, eb1}));
  }

#define RITR_INSTANTIATE(dim)                                                                    \
  template DistanceClass classify<dim>(ContactKind, const StencilVector<dim> &);              \
  template double        distance_sqr<dim>(ContactKind, const StencilVector<dim> &);          \
  template double        distance_sqr<dim>(ContactKind, const StencilVector<dim> &,           \
                                    StencilVector<dim> &, StencilMatrix<dim> &);       \
  template Eigen::Vector2d closest_point_parameters<dim>(const DistanceClass &,               \
                                                         const StencilVector<dim> &);         \
  template double point_point_distance_sqr<dim>(const Eigen::Matrix<double, dim, 1> &,        \
                                                const Eigen::Matrix<double, dim, 1> &);
  RITR_INSTANTIATE(1)
  RITR_INSTANTIATE(2)
  RITR_INSTANTIATE(3)
#undef RITR_INSTANTIATE

  template double point_edge_distance_sqr<2>(const Eigen::Vector2d &, const Eigen::Vector2d &,
                                             const Eigen::Vector2d &);
  template double point_edge_distance_sqr<3>(const Eigen::Vector3d &, const Eigen::Vector3d &,
                                             const Eigen::Vector3d &);
} // namespace ritr::contact
