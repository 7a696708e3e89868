#pragma once
// Squared distances between contact primitives, with IPC-style distance-type
// classification.
//
// A primitive pair is described by its stencil: the positions of its vertices stacked
// vertex-major into a vector of stencil_dofs<dim> entries, in the order
//   vertex_vertex:  (a, b)
//   point_edge:     (p, e0, e1)
//   point_triangle: (p, t0, t1, t2)
//   edge_edge:      (ea0, ea1, eb0, eb1)
// The squared distance d(x) is the minimum over the two primitives. Classification finds
// which sub-feature realises it (point-point, point-line, point-plane, line-line); the
// distance is then that feature's smooth closed-form expression, which has the same value
// and is differentiated instead of the min. Classification is redone at every evaluation,
// so d(x) is exact at any position (d is C1 across region boundaries).
//
// The typed kernels are templates on the scalar so that instantiating them with
// SecondOrderDual gives exact gradients and Hessians.
#include <ritr/common/second_order_dual.h>
#include <ritr/contact/collision_surface.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <initializer_list>
#include <limits>

namespace ritr::contact
{
  enum class DistanceType
  {
    point_point, // |x[s0] - x[s1]|^2
    point_line,  // point x[s0] to the infinite line through x[s1], x[s2]
    point_plane, // point x[s0] to the plane through x[s1], x[s2], x[s3] (3D)
    line_line    // line x[s0]x[s1] to line x[s2]x[s3] (3D)
  };

  // Number of stencil slots a distance type reads.
  constexpr int n_slots(const DistanceType type)
  {
    return type == DistanceType::point_point ? 2 : type == DistanceType::point_line ? 3 : 4;
  }

  // The active distance type and the stencil slots (local vertex indices) it reads.
  struct DistanceClass
  {
    DistanceType       type  = DistanceType::point_point;
    std::array<int, 4> slots = {{0, 1, -1, -1}};
  };

  // Number of vertices of a primitive pair's stencil.
  constexpr int n_stencil_vertices(const ContactKind kind)
  {
    return kind == ContactKind::vertex_vertex ? 2 : kind == ContactKind::point_edge ? 3 : 4;
  }

  // Stencil size of the (unique per dim) primitive pair kinds: 2 in 1D, 3 in 2D, 4 in 3D.
  template <int dim>
  constexpr int stencil_size = dim == 1 ? 2 : (dim == 2 ? 3 : 4);
  template <int dim>
  constexpr int stencil_dofs = dim * stencil_size<dim>;

  template <int dim>
  using StencilVector = Eigen::Matrix<double, stencil_dofs<dim>, 1>;
  template <int dim>
  using StencilMatrix = Eigen::Matrix<double, stencil_dofs<dim>, stencil_dofs<dim>>;

  // Edges whose squared sine of angle is below this are treated as parallel by the
  // edge-edge classification (the closest pair then lies on the boundary of the parameter
  // square; a line-line formula would divide by ~0).
  constexpr double parallel_threshold = 1e-20;

  // The stencil vector of the given points (at most stencil_size<dim>), stacked vertex-major;
  // slots not given are zero.
  template <int dim>
  StencilVector<dim> make_stencil(std::initializer_list<Eigen::Matrix<double, dim, 1>> points)
  {
    StencilVector<dim> x = StencilVector<dim>::Zero();
    int                i = 0;
    for (const auto &p : points)
      x.template segment<dim>(dim * i++) = p;
    return x;
  }

  // Which feature pair realises the distance. kind must be valid for dim.
  template <int dim>
  DistanceClass classify(ContactKind kind, const StencilVector<dim> &x);

  // Squared distance between the two primitives of the stencil.
  template <int dim>
  double distance_sqr(ContactKind kind, const StencilVector<dim> &x);

  // Squared distance with its exact gradient and Hessian w.r.t. the stencil dofs.
  template <int dim>
  double distance_sqr(ContactKind kind, const StencilVector<dim> &x, StencilVector<dim> &grad,
                      StencilMatrix<dim> &hess);

  // Closest-point parameters for the classified feature pair (used by friction):
  // point_line: alpha in the line, closest point (1-alpha) x[s1] + alpha x[s2];
  // point_plane: (beta1, beta2), closest point (1-b1-b2) x[s1] + b1 x[s2] + b2 x[s3];
  // line_line: (alpha, beta) on lines s0s1 and s2s3; point_point: unused.
  template <int dim>
  Eigen::Vector2d closest_point_parameters(const DistanceClass &cls, const StencilVector<dim> &x);

  // Convenience wrappers for single primitive pairs.
  template <int dim>
  double point_point_distance_sqr(const Eigen::Matrix<double, dim, 1> &a,
                                  const Eigen::Matrix<double, dim, 1> &b);
  template <int dim>
  double point_edge_distance_sqr(const Eigen::Matrix<double, dim, 1> &p,
                                 const Eigen::Matrix<double, dim, 1> &e0,
                                 const Eigen::Matrix<double, dim, 1> &e1);
  double point_triangle_distance_sqr(const Eigen::Vector3d &p, const Eigen::Vector3d &t0,
                                     const Eigen::Vector3d &t1, const Eigen::Vector3d &t2);
  double edge_edge_distance_sqr(const Eigen::Vector3d &ea0, const Eigen::Vector3d &ea1,
                                const Eigen::Vector3d &eb0, const Eigen::Vector3d &eb1);

  // ---- Typed kernels (templates on the scalar) -----------------------------------------

  template <typename S, int dim>
  using KernelPoint = std::array<S, dim>;
  template <typename S, int dim>
  using KernelStencil = std::array<KernelPoint<S, dim>, 4>;

  namespace kernels
  {
    template <typename S, int dim>
    KernelPoint<S, dim> sub(const KernelPoint<S, dim> &a, const KernelPoint<S, dim> &b)
    {
      KernelPoint<S, dim> r;
      for (int k = 0; k < dim; ++k)
        r[k] = a[k] - b[k];
      return r;
    }

    template <typename S, int dim>
    S dot(const KernelPoint<S, dim> &a, const KernelPoint<S, dim> &b)
    {
      S r = a[0] * b[0];
      for (int k = 1; k < dim; ++k)
        r += a[k] * b[k];
      return r;
    }

    template <typename S>
    KernelPoint<S, 3> cross(const KernelPoint<S, 3> &a, const KernelPoint<S, 3> &b)
    {
      return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
    }

    template <typename S, int dim>
    S point_point_sqr(const KernelPoint<S, dim> &a, const KernelPoint<S, dim> &b)
    {
      const auto d = sub<S, dim>(a, b);
      return dot<S, dim>(d, d);
    }

    // |(a - p) x (b - p)|^2 / |b - a|^2 (twice the triangle area over the base).
    template <typename S, int dim>
    S point_line_sqr(const KernelPoint<S, dim> &p, const KernelPoint<S, dim> &a,
                     const KernelPoint<S, dim> &b)
    {
      static_assert(dim >= 2, "no lines in 1D");
      const auto e  = sub<S, dim>(b, a);
      const auto ap = sub<S, dim>(p, a);
      if constexpr (dim == 2)
        {
          const S c = e[0] * ap[1] - e[1] * ap[0];
          return c * c / dot<S, 2>(e, e);
        }
      else
        {
          const auto c = cross<S>(e, ap);
          return dot<S, 3>(c, c) / dot<S, 3>(e, e);
        }
    }

    // (w.n)^2 / |n|^2: the squared length of the component of w along n, i.e. the squared
    // distance between the parallel planes with normal n through the two ends of w.
    template <typename S>
    S normal_component_sqr(const KernelPoint<S, 3> &w, const KernelPoint<S, 3> &n)
    {
      const S s = dot<S, 3>(w, n);
      return s * s / dot<S, 3>(n, n);
    }

    template <typename S>
    S point_plane_sqr(const KernelPoint<S, 3> &p, const KernelPoint<S, 3> &a,
                      const KernelPoint<S, 3> &b, const KernelPoint<S, 3> &c)
    {
      const auto n = cross<S>(sub<S, 3>(b, a), sub<S, 3>(c, a));
      return normal_component_sqr<S>(sub<S, 3>(p, a), n);
    }

    // The lines lie in parallel planes with normal ea x eb.
    template <typename S>
    S line_line_sqr(const KernelPoint<S, 3> &a0, const KernelPoint<S, 3> &a1,
                    const KernelPoint<S, 3> &b0, const KernelPoint<S, 3> &b1)
    {
      const auto n = cross<S>(sub<S, 3>(a1, a0), sub<S, 3>(b1, b0));
      return normal_component_sqr<S>(sub<S, 3>(b0, a0), n);
    }
  } // namespace kernels

  // The classified distance formula evaluated on stencil points x (any scalar type).
  template <int dim, typename S>
  S typed_distance_sqr(const DistanceClass &cls, const KernelStencil<S, dim> &x)
  {
    const auto &s = cls.slots;
    switch (cls.type)
      {
        case DistanceType::point_point:
          return kernels::point_point_sqr<S, dim>(x[s[0]], x[s[1]]);
        case DistanceType::point_line:
          if constexpr (dim >= 2)
            return kernels::point_line_sqr<S, dim>(x[s[0]], x[s[1]], x[s[2]]);
          break;
        case DistanceType::point_plane:
          if constexpr (dim == 3)
            return kernels::point_plane_sqr<S>(x[s[0]], x[s[1]], x[s[2]], x[s[3]]);
          break;
        case DistanceType::line_line:
          if constexpr (dim == 3)
            return kernels::line_line_sqr<S>(x[s[0]], x[s[1]], x[s[2]], x[s[3]]);
          break;
      }
    return S(std::numeric_limits<double>::quiet_NaN());
  }

  // Stencil vector -> kernel points, as plain doubles.
  template <int dim>
  KernelStencil<double, dim> to_kernel_points(const StencilVector<dim> &x)
  {
    KernelStencil<double, dim> p{};
    for (int i = 0; i < stencil_size<dim>; ++i)
      for (int k = 0; k < dim; ++k)
        p[i][k] = x[i * dim + k];
    return p;
  }

  // Stencil vector -> kernel points whose coordinates are the independent AD variables.
  template <int dim>
  KernelStencil<SecondOrderDual<stencil_dofs<dim>>, dim>
  to_dual_points(const StencilVector<dim> &x)
  {
    using Dual = SecondOrderDual<stencil_dofs<dim>>;
    KernelStencil<Dual, dim> p{};
    for (int i = 0; i < stencil_size<dim>; ++i)
      for (int k = 0; k < dim; ++k)
        p[i][k] = Dual::variable(i * dim + k, x[i * dim + k]);
    return p;
  }
} // namespace ritr::contact
